// Writes finished frames on a background thread while the next frame renders. The renderer keeps both
// cores busy tracing; a frame's PNG encode runs on one core, so overlapping it with the next frame's
// trace turns the write's time into throughput instead of a pause. One frame is in flight at most:
// submit() first waits for the previous write, so memory stays bounded and the order of the files on
// disk follows the frame order. A failed write is rethrown by the next submit() or by wait().
//
// The writes run on one thread the writer keeps for its lifetime, started by the first submit(): a
// thread started for each frame cost about 0.3% of a draft frame (issue 58, docs/performance-history.md).
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace stirrup::render {

class FrameWriter {
 public:
  FrameWriter() = default;
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;
  // Waits for the write in flight (without rethrowing: the owner's own exception is already leaving),
  // then ends the thread.
  ~FrameWriter();

  // Waits for the previous write (rethrowing its error), then starts `write` in the background.
  void submit(std::function<void()> write);

  // Waits for the write in flight, rethrowing its error.
  void wait();

 private:
  void run();
  // Waits, with `lock` held, until no write is queued or running.
  void waitIdle(std::unique_lock<std::mutex>& lock);

  std::mutex mutex_;
  std::condition_variable changed_;
  std::function<void()> job_;  // the write queued or running; empty when idle
  // The last write done, kept until the caller's next wait() (or submit()), which frees its captures (a
  // frame's image) on the caller's thread between frames, as when each write had its own thread. Freed
  // by the writer's thread while the next frame rendered, the image let malloc give the heap's top
  // back, and the next frames faulted it in again: up to 450 page faults a draft frame, 1 run in 3.
  std::function<void()> finished_;
  std::exception_ptr error_;   // the last write's failure, until rethrown
  bool stopping_ = false;
  std::thread thread_;  // last: started after the members it reads
};

}  // namespace stirrup::render
