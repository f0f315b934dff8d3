// farm_bench's steps on the loopback farm (testing/loopback_farm.h): each throws
// std::runtime_error, with the tail of the master's log, when the step fails.
#pragma once

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "testing/loopback_farm.h"

namespace radfarm::bench {

using testing::FarmPrograms;
using testing::LoopbackFarm;

// Starts radfarmd (warnings and errors logged) with `extra` flags and waits for its address.
void StartMaster(LoopbackFarm& farm, const std::vector<std::string>& extra = {});
void WaitForAgents(const LoopbackFarm& farm, size_t count);
int64_t Submit(const LoopbackFarm& farm, const std::string& job_file,
               const std::vector<std::string>& flags = {});
// Polls the job every 50 ms until it is done; throws if it fails, is cancelled or takes longer
// than `timeout`.
nlohmann::json WaitDone(const LoopbackFarm& farm, int64_t id, std::chrono::seconds timeout);
void Fetch(const LoopbackFarm& farm, int64_t id, const std::string& out_dir);

}  // namespace radfarm::bench
