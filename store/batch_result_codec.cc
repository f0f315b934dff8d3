#include "store/batch_result_codec.h"

#include <string>

namespace radfarm::store {
namespace {

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

}  // namespace

std::vector<uint8_t> EncodeBatchResult(const BatchResult& result) {
  std::vector<uint8_t> bytes(kBatchResultHeaderBytes + kBatchResultHitBytes * result.hits.size());
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

Result<BatchResult> DecodeBatchResult(std::span<const uint8_t> bytes) {
  if (bytes.size() < kBatchResultHeaderBytes) {
    return Error{"batch result blob of " + std::to_string(bytes.size()) +
                 " bytes, expected at least " + std::to_string(kBatchResultHeaderBytes)};
  }
  const uint8_t* in = bytes.data();
  BatchResult result;
  result.escaped_weight = Get<uint64_t>(in);
  result.escaped_rays = Get<uint64_t>(in);
  result.back_weight = Get<uint64_t>(in);
  result.back_rays = Get<uint64_t>(in);
  const uint64_t hits = Get<uint64_t>(in);
  const size_t room = (bytes.size() - kBatchResultHeaderBytes) / kBatchResultHitBytes;
  if (hits != room || (bytes.size() - kBatchResultHeaderBytes) % kBatchResultHitBytes != 0) {
    return Error{"batch result blob of " + std::to_string(bytes.size()) + " bytes does not hold " +
                 std::to_string(hits) + " hits"};
  }
  result.hits.resize(hits);
  for (size_t k = 0; k < hits; ++k) {
    PatchHits& hit = result.hits[k];
    hit.patch = Get<uint32_t>(in);
    hit.weight = Get<uint64_t>(in);
    if (hit.weight == 0 || (k > 0 && hit.patch <= result.hits[k - 1].patch)) {
      return Error{"batch result blob: hit " + std::to_string(k) +
                   " is out of patch order or has no weight"};
    }
  }
  return result;
}

}  // namespace radfarm::store
