#include "loop/frame_splitter.h"

#include <algorithm>

namespace radfarm::loop {
namespace {
// A buffer grown for one big frame is given back afterwards, so an idle connection that once
// received 16 MiB does not keep 16 MiB.
constexpr size_t kKeptCapacity = 64 * 1024;
}  // namespace

void WriteFramePrefix(uint32_t payload_bytes, uint8_t* out) {
  for (size_t i = 0; i < kFramePrefixBytes; ++i)
    out[i] = static_cast<uint8_t>(payload_bytes >> (8 * i));
}

uint32_t ReadFramePrefix(const uint8_t* bytes) {
  uint32_t value = 0;
  for (size_t i = 0; i < kFramePrefixBytes; ++i) value |= uint32_t{bytes[i]} << (8 * i);
  return value;
}

FrameSplitter::FrameSplitter(uint32_t max_payload_bytes, std::shared_ptr<FrameBudget> budget)
    : max_payload_bytes_(max_payload_bytes), budget_(std::move(budget)) {
  if (budget_) holder_ = budget_->Join([this](const std::string& reason) { Evicted(reason); });
}

FrameSplitter::~FrameSplitter() {
  if (budget_) budget_->Leave(holder_);
}

void FrameSplitter::Evicted(const std::string& reason) {
  error_ = reason;
  charged_ = 0;
  partial_.clear();
  partial_.shrink_to_fit();  // the memory goes now, not when the connection is freed
  if (on_evicted_) on_evicted_(reason);
}

Status FrameSplitter::Reserve(size_t bytes) {
  size_t capacity = partial_.capacity();
  if (bytes > capacity) capacity = std::min<size_t>(expected_, std::max(bytes, 2 * capacity));
  // A buffer kept from an earlier frame is the connection's own; only growth past it is charged.
  if (budget_ && capacity > charged_ && capacity > partial_.capacity()) {
    if (!budget_->Take(holder_, capacity - charged_)) {
      error_ = "frame of " + std::to_string(expected_) + " bytes refused at " +
               std::to_string(partial_.size()) + " bytes: unfinished frames already hold " +
               std::to_string(budget_->held()) + " of the " + std::to_string(budget_->limit()) +
               " bytes allowed (" + budget_->name() + ")";
      return Error{error_};
    }
    charged_ = capacity;
  }
  partial_.reserve(capacity);
  return Ok{};
}

void FrameSplitter::FrameDone() {
  partial_.clear();
  if (partial_.capacity() > kKeptCapacity) partial_.shrink_to_fit();
  if (budget_) budget_->Give(holder_, charged_);
  charged_ = 0;
}

Status FrameSplitter::Feed(std::span<const uint8_t> bytes, const OnPayload& on_payload) {
  if (failed()) return Error{error_};
  while (!bytes.empty()) {
    if (!in_payload_) {
      const size_t take = std::min(kFramePrefixBytes - prefix_have_, bytes.size());
      std::copy_n(bytes.begin(), take, prefix_.begin() + prefix_have_);
      prefix_have_ += take;
      bytes = bytes.subspan(take);
      if (prefix_have_ < kFramePrefixBytes) break;
      prefix_have_ = 0;
      expected_ = ReadFramePrefix(prefix_.data());
      if (expected_ > max_payload_bytes_) {
        error_ = "frame of " + std::to_string(expected_) + " bytes exceeds the limit of " +
                 std::to_string(max_payload_bytes_) + " bytes";
        return Error{error_};
      }
      in_payload_ = true;
    }
    if (partial_.empty() && bytes.size() >= expected_) {
      // The whole payload is in this chunk: hand it over without copying.
      in_payload_ = false;
      const std::span<const uint8_t> payload = bytes.first(expected_);
      bytes = bytes.subspan(expected_);
      if (!on_payload(payload)) return Ok{};
      continue;
    }
    const size_t take = std::min<size_t>(expected_ - partial_.size(), bytes.size());
    RADFARM_RETURN_IF_ERROR(Reserve(partial_.size() + take));
    partial_.insert(partial_.end(), bytes.begin(), bytes.begin() + static_cast<ptrdiff_t>(take));
    bytes = bytes.subspan(take);
    if (partial_.size() < expected_) break;
    in_payload_ = false;
    const bool go_on = on_payload(partial_);
    FrameDone();
    if (!go_on) return Ok{};
  }
  return Ok{};
}

}  // namespace radfarm::loop
