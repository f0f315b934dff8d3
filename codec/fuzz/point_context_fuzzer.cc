// libFuzzer target: arbitrary bytes through DecodePointContext, as an agent decodes the context a
// job's display points are traced against. Nothing may crash, leak, hang or read out of bounds or
// misaligned; a context that decodes must re-encode to bytes that decode and re-encode to the same
// bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "codec/patch_scene_codec.h"
#include "codec/point_context_blob.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace radfarm::codec;
  auto decoded = DecodePointContext(std::span(data, size));
  if (!decoded) return 0;
  const std::vector<uint8_t> once =
      EncodePointContext(EncodePatchScene(decoded->scene), decoded->context);
  auto again = DecodePointContext(once);
  if (!again || EncodePointContext(EncodePatchScene(again->scene), again->context) != once) {
    std::abort();
  }
  return 0;
}
