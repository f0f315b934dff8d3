// FrameSplitter: cuts a byte stream, in whatever chunks it arrives, into frames: a 4-byte
// little-endian payload length, then that many payload bytes (the wire format of
// docs/PROTOCOL.md; what the payload holds is protocol/'s business).
//
// Memory: the length is checked against the limit as soon as its 4 bytes are in, before anything
// is reserved for the payload, and the buffer grows only with bytes that actually arrived
// (doubling, to at most the frame's length), so a peer cannot make us allocate more than twice what
// it sends. With a FrameBudget, a partial frame's buffer is charged to it while the frame is
// unfinished; a growth it cannot cover fails the stream, or another's that holds more
// (set_on_evicted tells the owner of that one). Complete frames inside one chunk are
// passed straight from the chunk without copying. After an error the splitter stays failed: a byte
// stream cannot be resynchronised. Not thread-safe (one per connection).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "base/result.h"
#include "loop/frame_budget.h"

namespace radfarm::loop {

inline constexpr size_t kFramePrefixBytes = 4;

void WriteFramePrefix(uint32_t payload_bytes, uint8_t* out);
uint32_t ReadFramePrefix(const uint8_t* bytes);

class FrameSplitter {
 public:
  explicit FrameSplitter(uint32_t max_payload_bytes, std::shared_ptr<FrameBudget> budget = nullptr);
  ~FrameSplitter();
  FrameSplitter(const FrameSplitter&) = delete;
  FrameSplitter& operator=(const FrameSplitter&) = delete;

  // Called for each complete payload, valid during the call only. Returning false stops the
  // splitter at once; the rest of the chunk is dropped (the caller is closing the stream).
  using OnPayload = std::function<bool(std::span<const uint8_t> payload)>;

  // Changes the limit for the frames whose length has not arrived yet (a frame under way keeps
  // the limit it was checked against). Callable from on_payload: the next frame of the same
  // chunk is checked against the new limit.
  void set_max_payload_bytes(uint32_t max_payload_bytes) { max_payload_bytes_ = max_payload_bytes; }

  // Called when the budget evicts this splitter for another's frame (it is failed by then, its
  // buffer freed); the owner closes the stream. Never called from within this splitter's Feed.
  void set_on_evicted(std::function<void(const std::string& reason)> on_evicted) {
    on_evicted_ = std::move(on_evicted);
  }
  uint32_t max_payload_bytes() const { return max_payload_bytes_; }

  // Fails (and stays failed) on a length above the limit, or a partial frame the budget cannot
  // hold.
  Status Feed(std::span<const uint8_t> bytes, const OnPayload& on_payload);

  // Bytes of the current partial frame held here, and the memory reserved for them.
  size_t buffered_bytes() const { return prefix_have_ + partial_.size(); }
  size_t buffer_capacity() const { return partial_.capacity(); }
  bool failed() const { return !error_.empty(); }

 private:
  // Room for `bytes` of the partial frame, charged to the budget; fails the stream if it is full.
  Status Reserve(size_t bytes);
  // The partial frame was handed on: its buffer shrinks, its charge goes back.
  void FrameDone();
  void Evicted(const std::string& reason);

  uint32_t max_payload_bytes_;
  std::array<uint8_t, kFramePrefixBytes> prefix_{};
  size_t prefix_have_ = 0;
  bool in_payload_ = false;  // prefix complete, waiting for `expected_` payload bytes
  uint32_t expected_ = 0;
  std::vector<uint8_t> partial_;  // payload bytes of a frame split across chunks
  std::string error_;
  std::shared_ptr<FrameBudget> budget_;
  uint64_t holder_ = 0;   // this splitter in budget_
  uint64_t charged_ = 0;  // what the unfinished frame's buffer holds of the budget
  std::function<void(const std::string&)> on_evicted_;
};

}  // namespace radfarm::loop
