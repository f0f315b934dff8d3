// CPU-capped process groups: each a cgroup of its own whose processes share at most a fraction of
// one core, so that processes on one box behave like small machines of their own (bench/office/).
// The cap is the cgroup v1 `cpu` controller's `cpu.cfs_quota_us` over a 10 ms `cpu.cfs_period_us`,
// or cgroup v2's `cpu.max` ("QUOTA 10000"), whichever this machine has writable. A process joins a
// group by writing its pid to the group's `cgroup.procs` before it execs (ChildOptions in
// testing/child_process.h), so none of its work runs uncapped.
//
//   std::string why;
//   const std::optional<CpuController> cpu = FindCpuController(&why);
//   if (!cpu) return Skip(why);  // kNoCpuController
//   CpuGroup group(*cpu, "agent", 0.3);
//   ChildProcess agent(args, log, {.cgroup_procs = group.procs_path()});
#pragma once

#include <optional>
#include <string>

namespace radfarm::testing {

inline constexpr char kNoCpuController[] =
    "no writable cpu controller (cgroup v1 cpu or v2 cpu.max)";

// Where capped groups are made: the directory of this process's own cgroup in a cpu hierarchy.
struct CpuController {
  enum class Version { kV1, kV2 };
  Version version = Version::kV1;
  std::string parent;  // groups are made as its subdirectories
};

// The cpu controller this process may make capped groups in (v1 first, then v2), found by making
// and removing a probe group; nullopt with kNoCpuController and the paths tried in *why.
std::optional<CpuController> FindCpuController(std::string* why);

// A group capped at `share` of one core, removed by the destructor once its processes are gone
// (the caller kills and reaps them first; it waits up to 10 s for the kernel to let go of them).
// Not thread-safe; one owner.
class CpuGroup {
 public:
  // The smallest cap the v1 controller takes (a 1 ms quota of the 10 ms period).
  static constexpr double kMinShare = 0.1;

  // Makes PARENT/radfarm-NAME-PID-SERIAL and caps it. Throws std::runtime_error when the group
  // cannot be made or capped, or when `share` is outside [kMinShare, 64].
  CpuGroup(const CpuController& controller, const std::string& name, double share);
  ~CpuGroup();
  CpuGroup(const CpuGroup&) = delete;
  CpuGroup& operator=(const CpuGroup&) = delete;

  const std::string& path() const { return path_; }
  // The file a pid is written to to move that process into the group.
  std::string procs_path() const { return path_ + "/cgroup.procs"; }
  double share() const { return share_; }

 private:
  std::string path_;
  double share_;
};

}  // namespace radfarm::testing
