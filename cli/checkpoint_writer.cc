#include "cli/checkpoint_writer.h"

#include <utility>

namespace radfarm {

CheckpointWriter::CheckpointWriter(store::JobStore& store)
    : store_(store), thread_([this] { Loop(); }) {}

CheckpointWriter::~CheckpointWriter() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stopping_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

Status CheckpointWriter::Submit(Work work, bool checkpoint) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (!error_) return error_;
    queue_.emplace_back(std::move(work), checkpoint);
    if (checkpoint) ++checkpoints_;
  }
  cv_.notify_all();
  return Ok{};
}

bool CheckpointWriter::checkpoint_pending() {
  std::lock_guard<std::mutex> lock(mu_);
  return checkpoints_ > 0;
}

Status CheckpointWriter::Drain() {
  std::unique_lock<std::mutex> lock(mu_);
  cv_.wait(lock, [this] { return queue_.empty() && !busy_; });
  return error_;
}

void CheckpointWriter::Loop() {
  std::unique_lock<std::mutex> lock(mu_);
  while (true) {
    cv_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, and everything queued has run
    auto [work, checkpoint] = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    Status status = Ok{};
    if (error_) {
      lock.unlock();
      status = work(store_);
      lock.lock();
    }
    if (error_ && !status) error_ = std::move(status);
    if (checkpoint) --checkpoints_;
    busy_ = false;
    cv_.notify_all();
  }
}

}  // namespace radfarm
