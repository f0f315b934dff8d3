#include "daemon/console/web/stream_slots.h"

#include <algorithm>

namespace radfarm::web {

StreamSlots::Ticket::~Ticket() { slots_.Leave(this); }

StreamSlots::StreamSlots(const StatusBoard& board, size_t max, size_t max_per_address)
    : board_(board), max_(max), max_per_address_(max_per_address) {}

std::unique_ptr<StreamSlots::Ticket> StreamSlots::Join(const std::string& address) {
  std::unique_ptr<Ticket> ticket(new Ticket(*this, address));
  bool evicted = false;
  {
    std::lock_guard lock(mutex_);
    const auto own = [&] {
      return std::count_if(streams_.begin(), streams_.end(),
                           [&](const Ticket* t) { return t->address_ == address; });
    };
    while (!streams_.empty() && static_cast<size_t>(own()) >= max_per_address_) {
      EvictLocked(&address);
      evicted = true;
    }
    while (!streams_.empty() && streams_.size() >= max_) {
      EvictLocked(nullptr);
      evicted = true;
    }
    streams_.push_back(ticket.get());
  }
  if (evicted) board_.Wake();
  return ticket;
}

size_t StreamSlots::size() const {
  std::lock_guard lock(mutex_);
  return streams_.size();
}

void StreamSlots::Leave(Ticket* ticket) {
  std::lock_guard lock(mutex_);
  streams_.remove(ticket);
}

void StreamSlots::EvictLocked(const std::string* address) {
  for (auto it = streams_.begin(); it != streams_.end(); ++it) {
    if (address && (*it)->address_ != *address) continue;
    (*it)->evicted_ = true;
    streams_.erase(it);
    return;
  }
}

}  // namespace radfarm::web
