#include "daemon/jobs/start_handoff.h"

namespace radfarm::daemon {

StartAnswer StartHandoff::Await(StartRequest request) {
  std::unique_lock lock(mutex_);
  if (abandoned_) return Error{*abandoned_};
  const uint64_t ticket = next_ticket_++;
  waiting_.emplace_back(ticket, std::move(request));
  open_[ticket];
  wake_();
  answered_.wait(lock, [&] { return open_.at(ticket).has_value(); });
  StartAnswer answer = std::move(*open_.at(ticket));
  open_.erase(ticket);
  return answer;
}

std::vector<std::pair<uint64_t, StartRequest>> StartHandoff::Take() {
  std::lock_guard lock(mutex_);
  std::vector<std::pair<uint64_t, StartRequest>> taken(std::make_move_iterator(waiting_.begin()),
                                                       std::make_move_iterator(waiting_.end()));
  waiting_.clear();
  return taken;
}

void StartHandoff::Answer(uint64_t ticket, StartAnswer answer) {
  {
    std::lock_guard lock(mutex_);
    const auto it = open_.find(ticket);
    if (it == open_.end() || it->second) return;
    it->second = std::move(answer);
  }
  answered_.notify_all();
}

void StartHandoff::AbandonAll(const std::string& why) {
  {
    std::lock_guard lock(mutex_);
    abandoned_ = why;
    waiting_.clear();
    for (auto& [ticket, answer] : open_) {
      if (!answer) answer = StartAnswer(Error{why});
    }
  }
  answered_.notify_all();
}

}  // namespace radfarm::daemon
