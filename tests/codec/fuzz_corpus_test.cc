// The codec fuzzers' inputs in every build (docs/FUZZING.md): each seed, written by the encoders,
// decodes; each finding, an input that once broke a decoder, decodes to the same answer as before.
// Under -DRADFARM_SANITIZE=ON the findings would report their undefined behaviour again.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "codec/display_blob.h"
#include "codec/job_bundle.h"
#include "codec/job_solution.h"
#include "codec/point_context_blob.h"

namespace radfarm::codec {
namespace {

const std::filesystem::path kTests = std::filesystem::path(RADFARM_SOURCE_DIR) / "tests/codec";

std::vector<uint8_t> ReadBlob(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::filesystem::path> FilesIn(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path());
  EXPECT_FALSE(files.empty()) << dir;
  return files;
}

TEST(CodecFuzzCorpusTest, EverySeedDecodes) {
  for (const auto& path : FilesIn(kTests / "fuzz_corpus/job_bundle")) {
    Result<JobBundle> bundle = DecodeJobBundle(ReadBlob(path));
    EXPECT_TRUE(bundle.ok()) << path << ": " << bundle.error();
  }
  for (const auto& path : FilesIn(kTests / "fuzz_corpus/job_solution")) {
    Result<JobSolution> solution = DecodeJobSolution(ReadBlob(path));
    ASSERT_TRUE(solution.ok()) << path << ": " << solution.error();
    EXPECT_TRUE(DecodeJobBundle(solution->bundle).ok()) << path;
  }
  // The display fuzzer's input: the patch count, then the blob (display_blob_fuzzer.cc).
  for (const auto& path : FilesIn(kTests / "fuzz_corpus/display_blob")) {
    const std::vector<uint8_t> seed = ReadBlob(path);
    ASSERT_FALSE(seed.empty()) << path;
    Result<Display> display = DecodeDisplay(std::span(seed).subspan(1), seed[0]);
    EXPECT_TRUE(display.ok()) << path << ": " << display.error();
  }
  for (const auto& path : FilesIn(kTests / "fuzz_corpus/point_context")) {
    Result<DecodedPointContext> context = DecodePointContext(ReadBlob(path));
    EXPECT_TRUE(context.ok()) << path << ": " << context.error();
  }
}

// The fuzzer's first finding (UBSan: "member call on misaligned address ... BundlePoint"): a blob
// whose positions vector starts where 8 does not divide the address. The verifier accepts it; the
// positions are now copied out byte for byte instead of read through misaligned pointers.
TEST(CodecFuzzCorpusTest, JobBundlePositionsAtAMisalignedAddressAreCopiedOut) {
  const std::vector<uint8_t> blob =
      ReadBlob(kTests / "fuzz_findings/job_bundle/misaligned-positions.bin");
  // The four positions are read (and copied) before the faces, whose indices the fuzzer broke.
  Result<JobBundle> bundle = DecodeJobBundle(blob);
  ASSERT_FALSE(bundle.ok());
  EXPECT_EQ(bundle.error(), "job bundle: face 2 index out of range");
}

// The same for a job solution's radiosity colours (UBSan: "... SolutionColour").
TEST(CodecFuzzCorpusTest, JobSolutionColoursAtAMisalignedAddressAreCopiedOut) {
  const std::vector<uint8_t> blob =
      ReadBlob(kTests / "fuzz_findings/job_solution/misaligned-colours.bin");
  Result<JobSolution> solution = DecodeJobSolution(blob);
  ASSERT_FALSE(solution.ok());
  EXPECT_EQ(solution.error(), "job solution: unshot has a different size than radiosity");
}

}  // namespace
}  // namespace radfarm::codec
