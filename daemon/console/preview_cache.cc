#include "daemon/console/preview_cache.h"

#include <poll.h>
#include <sys/eventfd.h>

#include <algorithm>
#include <cerrno>

#include "loop/check.h"

namespace radfarm::daemon {

PreviewFlight::PreviewFlight() : done_(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK)) {
  LOOP_CHECK(done_.valid());
}

void PreviewFlight::Wake() {
  const uint64_t one = 1;
  LOOP_CHECK(::write(done_.get(), &one, sizeof one) == sizeof one);
}

bool PreviewFlight::cancelled() const {
  std::lock_guard lock(mutex_);
  return cancelled_;
}

bool PreviewFlight::finished() const {
  std::lock_guard lock(mutex_);
  return png_.has_value();
}

std::optional<Result<std::string>> PreviewFlight::Wait(int client_fd,
                                                       std::chrono::milliseconds timeout) const {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline = Clock::now() + timeout;
  while (true) {
    {
      std::lock_guard lock(mutex_);
      if (png_) return *png_;
    }
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return std::nullopt;
    // The eventfd stays readable once written, so every waiter sees it. POLLRDHUP: the client
    // closed its end (a pipelined next request is POLLIN alone, and is not a leave).
    pollfd fds[2] = {{done_.get(), POLLIN, 0}, {client_fd, POLLRDHUP, 0}};
    const int rc = ::poll(fds, client_fd >= 0 ? 2 : 1, static_cast<int>(left.count()));
    if (rc < 0 && errno == EINTR) continue;
    if (rc <= 0) return std::nullopt;
    if (client_fd >= 0 && (fds[1].revents & (POLLRDHUP | POLLHUP | POLLERR)) != 0) {
      std::lock_guard lock(mutex_);
      if (png_) return *png_;
      return std::nullopt;
    }
  }
}

PreviewCache::Joined PreviewCache::Join(const PreviewKey& key) {
  std::lock_guard lock(mutex_);
  if (const auto it = flights_.find(key); it != flights_.end()) {
    const std::shared_ptr<PreviewFlight>& flight = it->second;
    std::lock_guard flight_lock(flight->mutex_);
    ++flight->requesters_;
    ++shared_;
    if (flight->png_) {  // kept: now the most recently asked for
      recent_.remove(key);
      recent_.push_front(key);
    }
    return {flight, false};
  }
  // A newer checkpoint of the job: its older previews will not be asked for again.
  for (auto it = flights_.begin(); it != flights_.end();) {
    if (it->first.job == key.job && it->second->finished()) {
      recent_.remove(it->first);
      it = flights_.erase(it);
    } else {
      ++it;
    }
  }
  auto flight = std::make_shared<PreviewFlight>();
  flight->key_ = key;
  flight->requesters_ = 1;
  flights_[key] = flight;
  return {flight, true};
}

void PreviewCache::Leave(const std::shared_ptr<PreviewFlight>& flight) {
  std::lock_guard lock(mutex_);
  std::lock_guard flight_lock(flight->mutex_);
  --flight->requesters_;
  if (flight->requesters_ > 0 || flight->png_ || flight->cancelled_) return;
  flight->cancelled_ = true;
  ++cancelled_;
  Forget(flight.get());
}

void PreviewCache::Finish(const std::shared_ptr<PreviewFlight>& flight, Result<std::string> png) {
  std::lock_guard lock(mutex_);
  const bool ok = png.ok();
  bool cancelled = false;
  {
    std::lock_guard flight_lock(flight->mutex_);
    if (flight->png_) return;
    cancelled = flight->cancelled_;
    flight->png_ = std::move(png);
  }
  flight->Wake();
  if (cancelled) return;  // forgotten already; a newer flight of its key may be running
  if (!ok) {
    Forget(flight.get());  // the next request tries again
    return;
  }
  ++drawn_;
  recent_.push_front(flight->key_);
  while (recent_.size() > kMaxKept) {
    flights_.erase(recent_.back());
    recent_.pop_back();
  }
}

void PreviewCache::Close(const std::string& why) {
  std::lock_guard lock(mutex_);
  for (auto& [key, flight] : flights_) {
    {
      std::lock_guard flight_lock(flight->mutex_);
      if (flight->png_) continue;
      flight->png_ = Error{why};
    }
    flight->Wake();
  }
  flights_.clear();
  recent_.clear();
}

void PreviewCache::Forget(const PreviewFlight* flight) {
  const auto it = flights_.find(flight->key_);
  if (it == flights_.end() || it->second.get() != flight) return;
  recent_.remove(flight->key_);
  flights_.erase(it);
}

uint64_t PreviewCache::drawn() const {
  std::lock_guard lock(mutex_);
  return drawn_;
}

uint64_t PreviewCache::cancelled() const {
  std::lock_guard lock(mutex_);
  return cancelled_;
}

uint64_t PreviewCache::shared() const {
  std::lock_guard lock(mutex_);
  return shared_;
}

}  // namespace radfarm::daemon
