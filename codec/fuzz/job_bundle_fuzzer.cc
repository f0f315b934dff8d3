// libFuzzer target: arbitrary bytes through DecodeJobBundle, as the master decodes what `radfarm
// submit` sends. Nothing may crash, leak, hang or read out of bounds or misaligned; a bundle that
// decodes must re-encode to bytes that decode and re-encode to the same bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "codec/job_bundle.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace radfarm::codec;
  auto bundle = DecodeJobBundle(std::span(data, size));
  if (!bundle) return 0;
  const std::vector<uint8_t> once = EncodeJobBundle(*bundle);
  auto again = DecodeJobBundle(once);
  if (!again || EncodeJobBundle(*again) != once) std::abort();
  return 0;
}
