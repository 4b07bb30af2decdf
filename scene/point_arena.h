// Where a view's framing keeps the characters' points of every frame it frames (scene/view.h).
// A long shot keeps a hundred megabytes of them (every third vertex of a horse and rider, 600 frames),
// a few hundred kilobytes a frame. Allocated frame by frame, each block was fresh memory, and on these
// virtual machines the page faults of touching it took a fifth of a shot's set-up. The arena keeps them
// in large blocks the kernel may back with 2 MB pages (madvise MADV_HUGEPAGE; where transparent huge
// pages are off, it is ordinary memory), so a shot faults in a few hundred pages, not tens of thousands.
#pragma once

#include <cstddef>
#include <mutex>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace stirrup::scene {

class PointArena {
 public:
  PointArena() = default;
  ~PointArena();
  PointArena(const PointArena&) = delete;
  PointArena& operator=(const PointArena&) = delete;

  // A copy of `points`, valid while the arena lives. Safe to call from several threads at once.
  std::span<const glm::vec3> keep(std::span<const glm::vec3> points);
  // Bytes of the blocks held (a block is at least kBlockBytes).
  std::size_t reservedBytes() const;

  // A block's size: a multiple of the 2 MB huge page.
  static constexpr std::size_t kBlockBytes = std::size_t(32) << 20;

 private:
  struct Block {
    void* mapping;             // as mmap returned it, and its length
    std::size_t mapped_bytes;
    glm::vec3* data;           // its first huge page boundary, and the bytes used from there
    std::size_t bytes, used;   // used: points handed out
  };
  mutable std::mutex mutex_;
  std::vector<Block> blocks_;
};

}  // namespace stirrup::scene
