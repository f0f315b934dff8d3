#include "testing/cpu_cap.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "testing/child_process.h"

namespace radfarm::testing {
namespace {

constexpr long kPeriodMicros = 10000;

// Writes `text` to a cgroup file with one write(2), so the kernel's refusal is seen here.
void WriteControlFile(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  const bool ok = fd >= 0 && ::write(fd, text.data(), text.size()) == ssize_t(text.size());
  const int error = errno;
  if (fd >= 0) ::close(fd);
  if (!ok)
    throw std::runtime_error("cannot write '" + text + "' to " + path + ": " +
                             std::strerror(error));
}

bool HasToken(const std::string& list, const std::string& token) {
  std::stringstream items(list);
  for (std::string item; std::getline(items, item, ',');) {
    if (item == token) return true;
  }
  return false;
}

// This process's cgroup path in the hierarchy of `controller` (v1), or the v2 one for "".
std::string OwnCgroup(const std::string& controller) {
  std::ifstream in("/proc/self/cgroup");
  for (std::string line; std::getline(in, line);) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const bool match = controller.empty() ? line.substr(0, first) == "0" && controllers.empty()
                                          : HasToken(controllers, controller);
    if (match) return line.substr(second + 1);
  }
  return "/";
}

// Directories where capped groups might be made: for each cpu hierarchy mounted, this process's
// own group in it (or the mount's root when that is not visible here).
std::vector<CpuController> Candidates() {
  std::vector<CpuController> v1, v2;
  std::ifstream in("/proc/self/mounts");
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string device, mount, type, options;
    fields >> device >> mount >> type >> options;
    const bool is_v1 = type == "cgroup" && HasToken(options, "cpu");
    if (!is_v1 && type != "cgroup2") continue;
    std::string dir = mount + OwnCgroup(is_v1 ? "cpu" : "");
    while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
    if (!std::filesystem::is_directory(dir)) dir = mount;
    (is_v1 ? v1 : v2)
        .push_back({is_v1 ? CpuController::Version::kV1 : CpuController::Version::kV2, dir});
  }
  v1.insert(v1.end(), v2.begin(), v2.end());
  return v1;
}

}  // namespace

std::optional<CpuController> FindCpuController(std::string* why) {
  std::string tried;
  for (const CpuController& candidate : Candidates()) {
    if (candidate.version == CpuController::Version::kV2) {
      // A v2 group's children have cpu.max only where it hands them the controller; refused
      // (and then the probe fails) where the group itself holds processes.
      try {
        WriteControlFile(candidate.parent + "/cgroup.subtree_control", "+cpu");
      } catch (const std::runtime_error&) {
      }
    }
    try {
      const CpuGroup probe(candidate, "probe", 0.5);
      return candidate;
    } catch (const std::runtime_error& e) {
      tried += std::string("\n  ") + e.what();
    }
  }
  *why = std::string(kNoCpuController) + (tried.empty() ? ": no cgroup hierarchy mounted" : tried);
  return std::nullopt;
}

CpuGroup::CpuGroup(const CpuController& controller, const std::string& name, double share)
    : share_(share) {
  if (!(share >= kMinShare && share <= 64)) {
    throw std::runtime_error("a cpu share must be in [0.1, 64], not " + std::to_string(share));
  }
  static int serial = 0;
  path_ = controller.parent + "/radfarm-" + name + "-" + std::to_string(::getpid()) + "-" +
          std::to_string(serial++);
  if (::mkdir(path_.c_str(), 0755) != 0) {
    throw std::runtime_error("cannot make " + path_ + ": " + std::strerror(errno));
  }
  const long quota = std::lround(share * kPeriodMicros);
  try {
    if (controller.version == CpuController::Version::kV1) {
      WriteControlFile(path_ + "/cpu.cfs_period_us", std::to_string(kPeriodMicros));
      WriteControlFile(path_ + "/cpu.cfs_quota_us", std::to_string(quota));
    } else {
      WriteControlFile(path_ + "/cpu.max",
                       std::to_string(quota) + " " + std::to_string(kPeriodMicros));
    }
  } catch (...) {
    ::rmdir(path_.c_str());
    throw;
  }
}

CpuGroup::~CpuGroup() {
  // A reaped process may leave the group a moment later: rmdir says EBUSY until then.
  const bool removed = WaitUntil([&] { return ::rmdir(path_.c_str()) == 0 || errno != EBUSY; },
                                 std::chrono::seconds(10), std::chrono::milliseconds(10));
  if (!removed || std::filesystem::exists(path_)) {
    std::fprintf(stderr, "cannot remove the cpu group %s: %s\n", path_.c_str(),
                 std::strerror(errno));
  }
}

}  // namespace radfarm::testing
