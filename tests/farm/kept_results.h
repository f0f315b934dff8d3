// What radfarmd keeps of its rounds in progress (the store's round_results), read from its store
// file beside the running master (WAL lets readers in), for the restart tests.
#pragma once

#include <cstdint>
#include <string>

namespace radfarm::testing {

// Kept results of job `job` in all; -1 when the store cannot be read.
int64_t KeptResults(const std::string& db_path, int64_t job);

// The newest round with kept results of `job`, and how many it holds; round -1 when none.
struct KeptRound {
  int64_t round = -1;
  int64_t results = 0;
};
KeptRound NewestKeptRound(const std::string& db_path, int64_t job);

}  // namespace radfarm::testing
