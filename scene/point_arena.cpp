#include "scene/point_arena.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <new>

#include <sys/mman.h>

namespace stirrup::scene {
namespace {

constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;  // x86-64's transparent huge page

}  // namespace

PointArena::~PointArena() {
  for (const Block& b : blocks_) munmap(b.mapping, b.mapped_bytes);
}

std::span<const glm::vec3> PointArena::keep(std::span<const glm::vec3> points) {
  if (points.empty()) return {};
  glm::vec3* out = nullptr;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const std::size_t n = points.size();
    if (blocks_.empty() || (blocks_.back().bytes / sizeof(glm::vec3)) - blocks_.back().used < n) {
      // A new block, in huge pages where the kernel has them: mapped a huge page longer than used, so
      // that its start can be put on a huge page's boundary (the kernel backs only aligned 2 MB ranges).
      const std::size_t bytes = std::max(kBlockBytes, n * sizeof(glm::vec3));
      const std::size_t mapped = bytes + kHugePageBytes;
      void* p = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (p == MAP_FAILED) throw std::bad_alloc();
      const std::uintptr_t start = (reinterpret_cast<std::uintptr_t>(p) + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
      madvise(reinterpret_cast<void*>(start), bytes, MADV_HUGEPAGE);  // advice: without huge pages, no change
      blocks_.push_back({p, mapped, reinterpret_cast<glm::vec3*>(start), bytes, 0});
    }
    Block& b = blocks_.back();
    out = b.data + b.used;
    b.used += n;
  }
  // The copy outside the lock: the range is this call's alone.
  std::memcpy(out, points.data(), points.size() * sizeof(glm::vec3));
  return {out, points.size()};
}

std::size_t PointArena::reservedBytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::size_t bytes = 0;
  for (const Block& b : blocks_) bytes += b.bytes;
  return bytes;
}

}  // namespace stirrup::scene
