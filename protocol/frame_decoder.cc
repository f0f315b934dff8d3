#include "protocol/frame_decoder.h"

#include <utility>

#include "protocol/frame_codec.h"

namespace radfarm::protocol {

FrameDecoder::FrameDecoder(uint32_t max_frame_bytes) : max_frame_bytes_(max_frame_bytes) {}

Status FrameDecoder::Feed(std::span<const uint8_t> bytes) {
  if (failed()) return Error{error_};
  // Drop returned frames before growing, so the buffer holds about one frame plus one chunk.
  if (read_ > 0 && read_ >= buffer_.size() / 2) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(read_));
    read_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  return Ok{};
}

Result<std::optional<DecodedFrame>> FrameDecoder::Next() {
  Result<std::optional<std::vector<uint8_t>>> body = NextBody();
  if (!body) return Error{body.error()};
  if (!*body) return std::optional<DecodedFrame>();
  Result<DecodedFrame> frame = DecodeFrameBody(**body);
  if (!frame) return Fail(frame.error());
  return std::optional<DecodedFrame>(std::move(frame).value());
}

Result<std::optional<std::vector<uint8_t>>> FrameDecoder::NextBody() {
  if (failed()) return Error{error_};
  const size_t available = buffer_.size() - read_;
  if (available < kLengthPrefixBytes) return std::optional<std::vector<uint8_t>>();
  const uint32_t length = ReadLengthPrefix(buffer_.data() + read_);
  if (Status ok = CheckFrameLength(length, max_frame_bytes_); !ok) return Fail(ok.error());
  // Nothing is reserved from the length: the buffer grows only by bytes actually received.
  if (available - kLengthPrefixBytes < length) return std::optional<std::vector<uint8_t>>();
  const auto begin = buffer_.begin() + static_cast<std::ptrdiff_t>(read_ + kLengthPrefixBytes);
  std::vector<uint8_t> body(begin, begin + length);
  read_ += kLengthPrefixBytes + length;
  if (read_ == buffer_.size()) {
    buffer_.clear();
    read_ = 0;
  }
  return std::optional<std::vector<uint8_t>>(std::move(body));
}

Error FrameDecoder::Fail(std::string reason) {
  error_ = std::move(reason);
  buffer_.clear();
  buffer_.shrink_to_fit();
  read_ = 0;
  return Error{error_};
}

}  // namespace radfarm::protocol
