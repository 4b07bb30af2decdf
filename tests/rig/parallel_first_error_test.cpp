// rig/parallel_first_error.h: every item runs, and the error is the lowest failing item's at any
// thread count.
#include "rig/parallel_first_error.h"

#include <atomic>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

namespace stirrup::rig {
namespace {

TEST(ParallelFirstError, EveryItemRunsAndTheLowestFailureIsThrown) {
  for (int threads : {1, 2, 4}) {
    SCOPED_TRACE(threads);
    tbb::task_arena arena(threads);
    for (int run = 0; run < 20; ++run) {
      std::atomic<int> ran{0};
      std::string error = "(none)";
      arena.execute([&] {
        try {
          parallelForFirstError(200, [&](std::size_t i) {
            ++ran;
            if (i == 37 || i == 150 || i == 199) throw std::runtime_error("item " + std::to_string(i));
          });
        } catch (const std::runtime_error& e) {
          error = e.what();
        }
      });
      EXPECT_EQ(ran.load(), 200);
      EXPECT_EQ(error, "item 37");
    }
  }
  int sum = 0;
  EXPECT_NO_THROW(parallelForFirstError(0, [&](std::size_t) { ++sum; }));
  EXPECT_EQ(sum, 0);
}

}  // namespace
}  // namespace stirrup::rig
