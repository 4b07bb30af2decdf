#include "render/tracer/frame_writer.h"

#include <atomic>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace stirrup::render {
namespace {

using namespace std::chrono_literals;

TEST(FrameWriter, WritesInOrderWithOneInFlight) {
  std::vector<int> order;
  std::atomic<int> running{0}, most{0};
  {
    FrameWriter writer;
    for (int i = 0; i < 6; ++i) {
      writer.submit([&, i] {
        const int now = ++running;
        most = std::max(most.load(), now);
        std::this_thread::sleep_for(2ms);
        order.push_back(i);  // safe: submit waits for the previous job before starting this one
        --running;
      });
    }
    writer.wait();
  }
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(most.load(), 1);
}

TEST(FrameWriter, RunsBesideTheCaller) {
  // The job runs while the caller goes on: the caller sees it started before it finished.
  std::atomic<bool> started{false}, release{false};
  FrameWriter writer;
  writer.submit([&] {
    started = true;
    while (!release) std::this_thread::sleep_for(1ms);
  });
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (!started && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(1ms);
  EXPECT_TRUE(started.load());
  release = true;
  writer.wait();
}

TEST(FrameWriter, AFailedWriteIsRethrownByTheNextSubmitOrWait) {
  FrameWriter writer;
  writer.submit([] { throw std::runtime_error("cannot write a.png: disk full"); });
  bool ran = false;
  EXPECT_THROW(writer.submit([&] { ran = true; }), std::runtime_error);
  EXPECT_FALSE(ran);  // the failure stops the sequence before the next write starts
  writer.submit([] { throw std::runtime_error("cannot write b.png"); });
  try {
    writer.wait();
    ADD_FAILURE() << "wait() did not rethrow";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot write b.png");
  }
  EXPECT_NO_THROW(writer.wait());  // nothing in flight any more
}

TEST(FrameWriter, EveryWriteRunsOnTheOneThreadItKeeps) {
  // One thread for the writer's lifetime, not one a frame, and never the caller's.
  std::vector<std::thread::id> ids;
  FrameWriter writer;
  for (int i = 0; i < 5; ++i) writer.submit([&] { ids.push_back(std::this_thread::get_id()); });
  writer.wait();
  ASSERT_EQ(ids.size(), 5u);
  for (const std::thread::id id : ids) EXPECT_EQ(id, ids.front());
  EXPECT_NE(ids.front(), std::this_thread::get_id());
}

TEST(FrameWriter, AWritesCapturesAreFreedOnTheCallersThread) {
  // A write's captures (a frame's image) are freed by the caller's next wait(), between frames, not by
  // the writer's thread while the next frame renders (frame_writer.h says why: page faults).
  struct Probe {
    std::thread::id* freed_on;
    ~Probe() { *freed_on = std::this_thread::get_id(); }
  };
  std::thread::id freed_on, wrote_on;
  FrameWriter writer;
  auto probe = std::make_shared<Probe>(&freed_on);
  writer.submit([probe, &wrote_on] { wrote_on = std::this_thread::get_id(); });
  probe.reset();
  writer.wait();
  EXPECT_EQ(freed_on, std::this_thread::get_id());
  EXPECT_NE(wrote_on, std::this_thread::get_id());
}

TEST(FrameWriter, TheDestructorWaitsForTheWriteInFlight) {
  std::atomic<bool> done{false};
  {
    FrameWriter writer;
    writer.submit([&] {
      std::this_thread::sleep_for(20ms);
      done = true;
    });
  }
  EXPECT_TRUE(done.load());
}

}  // namespace
}  // namespace stirrup::render
