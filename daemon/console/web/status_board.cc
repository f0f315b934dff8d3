#include "daemon/console/web/status_board.h"

#include <utility>

namespace radfarm::web {

void StatusBoard::Publish(StatusSnapshot snapshot) {
  {
    std::lock_guard lock(mutex_);
    snapshot.version = ++version_;
    latest_ = std::make_shared<const StatusSnapshot>(std::move(snapshot));
  }
  changed_.notify_all();
}

std::shared_ptr<const StatusSnapshot> StatusBoard::Latest() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

std::shared_ptr<const StatusSnapshot> StatusBoard::WaitNewer(
    uint64_t version, std::chrono::steady_clock::time_point deadline,
    const std::atomic<bool>* stop) const {
  std::unique_lock lock(mutex_);
  changed_.wait_until(lock, deadline,
                      [&] { return closed_ || version_ > version || (stop && stop->load()); });
  if (closed_) return nullptr;
  return latest_;
}

void StatusBoard::Wake() const {
  // Under the mutex, so a waiter between its check of `stop` and its wait cannot miss it.
  { std::lock_guard lock(mutex_); }
  changed_.notify_all();
}

void StatusBoard::Close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
}

bool StatusBoard::closed() const {
  std::lock_guard lock(mutex_);
  return closed_;
}

}  // namespace radfarm::web
