// libFuzzer target: arbitrary bytes through DecodeDisplay, as `radfarm fetch` decodes the display
// the master drew. The first byte is the patch count the display is checked against, the rest the
// blob (so the blob is misaligned: the decoder copies it). Nothing may crash, leak, hang or read
// out of bounds or misaligned; a display that decodes must re-encode to bytes that decode and
// re-encode to the same bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "codec/display_blob.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace radfarm::codec;
  if (size < 1) return 0;
  const size_t patch_count = data[0];
  auto display = DecodeDisplay(std::span(data + 1, size - 1), patch_count);
  if (!display) return 0;
  const std::vector<uint8_t> once = EncodeDisplay(*display);
  auto again = DecodeDisplay(once, patch_count);
  if (!again || EncodeDisplay(*again) != once) std::abort();
  return 0;
}
