// EventStream: one browser's server-sent event stream (GET /api/events): the latest status
// snapshot at once, then each newer one as the loop thread publishes it, and a comment line every
// kKeepAlive so proxies and the browser see the connection alive. It waits on the StatusBoard,
// never on the loop.
//
//   retry: 2000
//
//   event: status
//   data: {"time_ms":...,"jobs":[...],"agents":[...],"events":[...]}
//
// A stream evicted by a newer one (stream_slots.h) sends a last event, then ends; the page waits
// `retry_ms` before it connects again:
//
//   event: evicted
//   data: {"retry_ms":30000}
//
// One HTTP thread reads it (thread-per-connection): Read blocks until it has bytes, and returns
// 0 once the board closes or the stream was evicted (the stream ends).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "daemon/console/web/status_board.h"
#include "daemon/console/web/stream_slots.h"

namespace radfarm::web {

class EventStream {
 public:
  static constexpr std::chrono::seconds kKeepAlive{15};
  static constexpr std::chrono::seconds kRetryAfterEviction{30};

  // `ticket` (null: never evicted) is the stream's place in the StreamSlots.
  explicit EventStream(const StatusBoard& board,
                       std::unique_ptr<StreamSlots::Ticket> ticket = nullptr)
      : board_(board), ticket_(std::move(ticket)) {}

  // Copies up to `max` bytes of the stream into `out`; 0 at the end.
  size_t Read(char* out, size_t max);

 private:
  // Waits for the next thing to send; false when the board closed.
  bool Refill();

  const StatusBoard& board_;
  std::unique_ptr<StreamSlots::Ticket> ticket_;
  bool ended_ = false;
  uint64_t sent_version_ = 0;
  std::string pending_ = "retry: 2000\n\n";
  size_t offset_ = 0;
};

}  // namespace radfarm::web
