#include "daemon/console/web/connection_deadlines.h"

#include <utility>

namespace radfarm::web {

ConnectionDeadlines::ConnectionDeadlines(std::chrono::milliseconds deadline, size_t max_waiting,
                                         size_t max_waiting_per_address)
    : deadline_(deadline),
      max_waiting_(max_waiting),
      max_waiting_per_address_(max_waiting_per_address) {}

std::vector<int> ConnectionDeadlines::Opened(Key key, std::string address, int fd, TimePoint now) {
  connections_[key] = Connection{std::move(address), fd, now};
  Waiting(key, now);
  std::vector<int> close;
  const std::string& own = connections_[key].address;
  while (waiting_per_address_[own] > max_waiting_per_address_) close.push_back(TakeOldest(own));
  while (waiting_.size() > max_waiting_) close.push_back(TakeOldest(""));
  return close;
}

void ConnectionDeadlines::Serving(Key key) { Unqueue(key); }

void ConnectionDeadlines::Waiting(Key key, TimePoint now) {
  auto it = connections_.find(key);
  if (it == connections_.end() || queued_.count(key)) return;
  it->second.deadline = now + deadline_;
  queued_[key] = waiting_.insert(waiting_.end(), key);
  ++waiting_per_address_[it->second.address];
}

void ConnectionDeadlines::Closed(Key key) {
  Unqueue(key);
  connections_.erase(key);
}

std::vector<int> ConnectionDeadlines::Expired(TimePoint now) {
  std::vector<int> close;
  // Queued in the order their deadlines were set, so the expired ones lead.
  while (!waiting_.empty() && connections_.at(waiting_.front()).deadline <= now) {
    const Key key = waiting_.front();
    close.push_back(connections_.at(key).fd);
    Unqueue(key);
  }
  return close;
}

void ConnectionDeadlines::Unqueue(Key key) {
  auto it = queued_.find(key);
  if (it == queued_.end()) return;
  waiting_.erase(it->second);
  queued_.erase(it);
  const std::string& address = connections_.at(key).address;
  if (--waiting_per_address_[address] == 0) waiting_per_address_.erase(address);
}

int ConnectionDeadlines::TakeOldest(const std::string& address) {
  for (const Key key : waiting_) {
    const Connection& c = connections_.at(key);
    if (!address.empty() && c.address != address) continue;
    const int fd = c.fd;
    Unqueue(key);
    return fd;
  }
  return -1;
}

}  // namespace radfarm::web
