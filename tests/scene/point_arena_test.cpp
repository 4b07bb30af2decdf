#include "scene/point_arena.h"

#include <algorithm>
#include <cstdint>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace stirrup::scene {
namespace {

std::vector<glm::vec3> ramp(std::size_t n, float from) {
  std::vector<glm::vec3> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = {from + float(i), -float(i), 0.5f * float(i)};
  return v;
}

// What the arena keeps is the points given, in order, at an address of its own that later calls leave
// alone (the framing reads every frame's points after the last frame was kept).
TEST(PointArena, KeepsACopyThatLaterCallsLeaveAlone) {
  PointArena arena;
  std::vector<glm::vec3> a = ramp(1000, 0.0f);
  const std::span<const glm::vec3> kept_a = arena.keep(a);
  ASSERT_EQ(kept_a.size(), a.size());
  EXPECT_NE(kept_a.data(), a.data());
  const std::vector<glm::vec3> expected = a;
  a.assign(a.size(), glm::vec3(7.0f));  // the caller's buffer reused for the next frame
  std::vector<std::span<const glm::vec3>> later;
  for (int k = 0; k < 50; ++k) later.push_back(arena.keep(ramp(5000, float(k))));
  EXPECT_TRUE(std::equal(kept_a.begin(), kept_a.end(), expected.begin()));
  for (int k = 0; k < 50; ++k) {
    const std::vector<glm::vec3> want = ramp(5000, float(k));
    EXPECT_TRUE(std::equal(later[std::size_t(k)].begin(), later[std::size_t(k)].end(), want.begin())) << k;
  }
  EXPECT_TRUE(arena.keep({}).empty());
}

// A block fills and the next one starts: 3 MB of points in 32 MB blocks fill one block; 40 MB need
// two, and a frame larger than a block gets a block of its own, whole.
TEST(PointArena, BlocksAreHugePageAlignedAndGrowAsNeeded) {
  PointArena arena;
  const std::span<const glm::vec3> first = arena.keep(ramp(250'000, 0.0f));  // 3 MB
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(first.data()) % (std::uintptr_t(2) << 20), 0u);
  EXPECT_EQ(arena.reservedBytes(), PointArena::kBlockBytes);
  const std::size_t big = PointArena::kBlockBytes / sizeof(glm::vec3) + 10;  // over a block
  const std::span<const glm::vec3> whole = arena.keep(ramp(big, 1.0f));
  ASSERT_EQ(whole.size(), big);
  EXPECT_EQ(whole.back(), ramp(big, 1.0f).back());
  EXPECT_GE(arena.reservedBytes(), PointArena::kBlockBytes + big * sizeof(glm::vec3));
}

// Frames are kept from several threads at once; each gets its own range, none overlapping.
TEST(PointArena, ThreadsGetRangesOfTheirOwn) {
  PointArena arena;
  constexpr int kThreads = 4, kFrames = 200;
  std::vector<std::vector<std::span<const glm::vec3>>> got(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      for (int f = 0; f < kFrames; ++f) got[std::size_t(t)].push_back(arena.keep(ramp(3000, float(t * 1000 + f))));
    });
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t)
    for (int f = 0; f < kFrames; ++f) {
      const std::vector<glm::vec3> want = ramp(3000, float(t * 1000 + f));
      ASSERT_TRUE(std::equal(got[std::size_t(t)][std::size_t(f)].begin(), got[std::size_t(t)][std::size_t(f)].end(),
                             want.begin()))
          << t << " " << f;
    }
}

}  // namespace
}  // namespace stirrup::scene
