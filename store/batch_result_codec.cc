#include "store/batch_result_codec.h"

#include <algorithm>
#include <optional>
#include <string>

#include "core/packed_hits.h"

namespace radfarm::store {
namespace {

constexpr uint8_t kMagic[4] = {'R', 'F', 'H', '2'};
constexpr size_t kFormat1HeaderBytes = 40;
constexpr size_t kFormat1HitBytes = 12;

// --- Format 2: LEB128 varints (core/packed_hits.h) ---------------------------------------------

Status CheckHit(const BatchResult& result, size_t k) {
  if (result.hits[k].weight == 0 || (k > 0 && result.hits[k].patch <= result.hits[k - 1].patch)) {
    return Error{"batch result blob: hit " + std::to_string(k) +
                 " is out of patch order or has no weight"};
  }
  return Ok{};
}

Result<BatchResult> DecodeFormat2(std::span<const uint8_t> bytes) {
  size_t in = sizeof kMagic;
  uint64_t header[5];
  for (uint64_t& v : header) {
    const std::optional<uint64_t> value = ReadVarint(bytes, &in);
    if (!value) {
      return Error{"batch result blob of " + std::to_string(bytes.size()) +
                   " bytes ends inside a number"};
    }
    v = *value;
  }
  BatchResult result;
  result.escaped_weight = header[0];
  result.escaped_rays = header[1];
  result.back_weight = header[2];
  result.back_rays = header[3];
  const std::string wrong = ReadPackedHits(bytes, &in, header[4], &result.hits);
  if (!wrong.empty()) {
    return Error{"batch result blob of " + std::to_string(bytes.size()) + " bytes: " + wrong};
  }
  if (in != bytes.size()) {
    return Error{"batch result blob: " + std::to_string(bytes.size() - in) +
                 " bytes after its last hit"};
  }
  return result;
}

// --- Format 1: fixed-width little-endian --------------------------------------------------------

template <typename T>
void Put(T value, uint8_t*& out) {
  for (size_t i = 0; i < sizeof(T); ++i) *out++ = static_cast<uint8_t>(uint64_t{value} >> (8 * i));
}

template <typename T>
T Get(const uint8_t*& in) {
  uint64_t value = 0;
  for (size_t i = 0; i < sizeof(T); ++i) value |= uint64_t{*in++} << (8 * i);
  return static_cast<T>(value);
}

Result<BatchResult> DecodeFormat1(std::span<const uint8_t> bytes) {
  if (bytes.size() < kFormat1HeaderBytes) {
    return Error{"batch result blob of " + std::to_string(bytes.size()) +
                 " bytes, expected at least " + std::to_string(kFormat1HeaderBytes)};
  }
  const uint8_t* in = bytes.data();
  BatchResult result;
  result.escaped_weight = Get<uint64_t>(in);
  result.escaped_rays = Get<uint64_t>(in);
  result.back_weight = Get<uint64_t>(in);
  result.back_rays = Get<uint64_t>(in);
  const uint64_t hits = Get<uint64_t>(in);
  const size_t room = (bytes.size() - kFormat1HeaderBytes) / kFormat1HitBytes;
  if (hits != room || (bytes.size() - kFormat1HeaderBytes) % kFormat1HitBytes != 0) {
    return Error{"batch result blob of " + std::to_string(bytes.size()) + " bytes does not hold " +
                 std::to_string(hits) + " hits"};
  }
  result.hits.resize(hits);
  for (size_t k = 0; k < hits; ++k) {
    result.hits[k].patch = Get<uint32_t>(in);
    result.hits[k].weight = Get<uint64_t>(in);
    RADFARM_RETURN_IF_ERROR(CheckHit(result, k));
  }
  return result;
}

}  // namespace

std::vector<uint8_t> EncodeBatchResult(const BatchResult& result) {
  std::vector<uint8_t> bytes(std::begin(kMagic), std::end(kMagic));
  bytes.reserve(sizeof kMagic + 5 * 10 + 3 * result.hits.size());
  for (uint64_t v : {result.escaped_weight, result.escaped_rays, result.back_weight,
                     result.back_rays, uint64_t{result.hits.size()}}) {
    AppendVarint(v, &bytes);
  }
  AppendPackedHits(result.hits, &bytes);
  return bytes;
}

Result<BatchResult> DecodeBatchResult(std::span<const uint8_t> bytes) {
  if (bytes.size() >= sizeof kMagic &&
      std::equal(std::begin(kMagic), std::end(kMagic), bytes.begin())) {
    return DecodeFormat2(bytes);
  }
  return DecodeFormat1(bytes);
}

std::vector<uint8_t> EncodeBatchResultFormat1(const BatchResult& result) {
  std::vector<uint8_t> bytes(kFormat1HeaderBytes + kFormat1HitBytes * result.hits.size());
  uint8_t* out = bytes.data();
  for (uint64_t v : {result.escaped_weight, result.escaped_rays, result.back_weight,
                     result.back_rays, uint64_t{result.hits.size()}}) {
    Put(v, out);
  }
  for (const PatchHits& hit : result.hits) {
    Put(hit.patch, out);
    Put(hit.weight, out);
  }
  return bytes;
}

}  // namespace radfarm::store
