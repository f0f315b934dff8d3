// libFuzzer target: arbitrary bytes as one control socket request frame, through the parsing the
// control server does (ParseControlJson, ParseControlRequest) and the error answer it would send.
// Any bytes, non-UTF-8 included, must give a request or an error: never an exception or abort.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "daemon/control/control_request_parser.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace radfarm::daemon;
  const std::span<const uint8_t> payload(data, size);
  auto json = ParseControlJson(payload);
  if (!json) {
    (void)JsonText(ControlError("bad_request", json.error()).body);
    return 0;
  }
  uint64_t attachment_bytes = 0;
  auto request = ParseControlRequest(*json, &attachment_bytes);
  if (!request) {
    (void)JsonText(ControlError("bad_request", request.error()).body);
    return 0;
  }
  const bool submit = request->command == ControlCommand::kSubmit;
  if (submit != (attachment_bytes > 0) || attachment_bytes > kMaxControlAttachmentBytes) {
    std::abort();
  }
  return 0;
}
