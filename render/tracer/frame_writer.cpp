#include "render/tracer/frame_writer.h"

#include <utility>

namespace stirrup::render {

FrameWriter::~FrameWriter() {
  if (!thread_.joinable()) return;
  {
    std::unique_lock lock(mutex_);
    waitIdle(lock);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void FrameWriter::submit(std::function<void()> write) {
  wait();
  {
    std::lock_guard lock(mutex_);
    job_ = std::move(write);
  }
  if (!thread_.joinable()) thread_ = std::thread([this] { run(); });
  changed_.notify_all();
}

void FrameWriter::wait() {
  std::function<void()> finished;  // freed when this returns, on the caller's thread
  std::unique_lock lock(mutex_);
  waitIdle(lock);
  finished = std::move(finished_);
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void FrameWriter::waitIdle(std::unique_lock<std::mutex>& lock) {
  changed_.wait(lock, [this] { return !job_; });
}

void FrameWriter::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return job_ || stopping_; });
    if (!job_) return;  // stopping, nothing queued
    lock.unlock();
    std::exception_ptr error;
    try {
      job_();
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    finished_ = std::move(job_);  // its captures are freed by the caller's next wait() (frame_writer.h)
    job_ = nullptr;
    error_ = error;
    changed_.notify_all();
  }
}

}  // namespace stirrup::render
