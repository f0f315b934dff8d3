// libFuzzer target: arbitrary bytes through DecodeJobSolution, as `radfarm fetch` decodes what the
// master sends. Nothing may crash, leak, hang or read out of bounds or misaligned; a solution that
// decodes must re-encode to bytes that decode and re-encode to the same bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "codec/job_solution.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace radfarm::codec;
  auto solution = DecodeJobSolution(std::span(data, size));
  if (!solution) return 0;
  const std::vector<uint8_t> once = EncodeJobSolution(*solution);
  auto again = DecodeJobSolution(once);
  if (!again || EncodeJobSolution(*again) != once) std::abort();
  return 0;
}
