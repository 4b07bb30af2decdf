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
  std::unique_lock lock(mutex_);
  waitIdle(lock);
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
    job_ = nullptr;  // the job's captures (a frame's image) are freed here, before the caller goes on
    error_ = error;
    changed_.notify_all();
  }
}

}  // namespace stirrup::render
