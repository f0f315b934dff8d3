#include "bench/farm/farm_checks.h"

#include <stdexcept>

namespace radfarm::bench {
namespace {

// The last lines of a log, for error messages.
std::string Tail(const std::string& text, size_t lines = 15) {
  size_t pos = text.size();
  for (size_t n = 0; n <= lines && pos > 0; ++n) pos = text.rfind('\n', pos - 1);
  return pos == std::string::npos ? text : text.substr(pos + 1);
}

[[noreturn]] void Fail(const LoopbackFarm& farm, const std::string& what) {
  const std::string log = farm.MasterLog();
  throw std::runtime_error(what + (log.empty() ? "" : "\nmaster log (tail):\n" + Tail(log)));
}

}  // namespace

void StartMaster(LoopbackFarm& farm, const std::vector<std::string>& extra) {
  std::vector<std::string> flags = {"--log-level", "warning"};
  flags.insert(flags.end(), extra.begin(), extra.end());
  farm.StartMaster(flags);
  if (farm.master_address().empty()) Fail(farm, "radfarmd wrote no listen.addr");
}

void WaitForAgents(const LoopbackFarm& farm, size_t count) {
  if (!farm.WaitForAgents(count, std::chrono::seconds(60))) {
    Fail(farm, "fewer than " + std::to_string(count) + " agents connected");
  }
}

int64_t Submit(const LoopbackFarm& farm, const std::string& job_file,
               const std::vector<std::string>& flags) {
  std::string error;
  const int64_t id = farm.Submit(job_file, flags, &error);
  if (id < 0) Fail(farm, error);
  return id;
}

nlohmann::json WaitDone(const LoopbackFarm& farm, int64_t id, std::chrono::seconds timeout) {
  const nlohmann::json job =
      farm.WaitForJob(id, testing::IsFinished, timeout, std::chrono::milliseconds(50));
  const std::string state = job.is_object() ? job.value("state", "") : "";
  if (state == "done") return job;
  Fail(farm, "job " + std::to_string(id) + " is " + (state.empty() ? "unknown" : state) +
                 (testing::IsFinished(job) ? ": " + job.dump()
                                           : " after " + std::to_string(timeout.count()) + " s"));
}

void Fetch(const LoopbackFarm& farm, int64_t id, const std::string& out_dir) {
  const testing::CommandResult r = farm.Fetch(id, out_dir);
  if (r.exit_code != 0) Fail(farm, "radfarm fetch " + std::to_string(id) + " failed: " + r.err);
}

}  // namespace radfarm::bench
