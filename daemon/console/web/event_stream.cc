#include "daemon/console/web/event_stream.h"

#include <algorithm>
#include <cstring>

namespace radfarm::web {

size_t EventStream::Read(char* out, size_t max) {
  if (offset_ == pending_.size() && !Refill()) return 0;
  const size_t n = std::min(max, pending_.size() - offset_);
  std::memcpy(out, pending_.data() + offset_, n);
  offset_ += n;
  return n;
}

bool EventStream::Refill() {
  if (ended_) return false;
  const std::atomic<bool>* stop = ticket_ ? &ticket_->evicted_flag() : nullptr;
  auto snapshot =
      board_.WaitNewer(sent_version_, std::chrono::steady_clock::now() + kKeepAlive, stop);
  if (board_.closed()) return false;
  offset_ = 0;
  if (ticket_ && ticket_->evicted()) {
    ended_ = true;
    pending_ = "event: evicted\ndata: {\"retry_ms\":" +
               std::to_string(std::chrono::milliseconds(kRetryAfterEviction).count()) + "}\n\n";
    return true;
  }
  if (!snapshot || snapshot->version <= sent_version_) {
    pending_ = ": keep-alive\n\n";
    return true;
  }
  sent_version_ = snapshot->version;
  // status_json is one line (JSON escapes newlines inside strings), so one data: field holds it.
  pending_ = "event: status\ndata: " + snapshot->status_json + "\n\n";
  return true;
}

}  // namespace radfarm::web
