// Writes finished frames on a background thread while the next frame renders. The renderer keeps both
// cores busy tracing; a frame's PNG encode runs on one core, so overlapping it with the next frame's
// trace turns the write's time into throughput instead of a pause. One frame is in flight at most:
// submit() first waits for the previous write, so memory stays bounded and the order of the files on
// disk follows the frame order. A failed write is rethrown by the next submit() or by wait().
#pragma once

#include <functional>
#include <future>

namespace stirrup::render {

class FrameWriter {
 public:
  FrameWriter() = default;
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;
  // Waits for the write in flight (without rethrowing: the owner's own exception is already leaving).
  ~FrameWriter() {
    if (pending_.valid()) pending_.wait();
  }

  // Waits for the previous write (rethrowing its error), then starts `write` in the background.
  void submit(std::function<void()> write) {
    wait();
    pending_ = std::async(std::launch::async, std::move(write));
  }

  // Waits for the write in flight, rethrowing its error.
  void wait() {
    if (pending_.valid()) pending_.get();
  }

 private:
  std::future<void> pending_;
};

}  // namespace stirrup::render
