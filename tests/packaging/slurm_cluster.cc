#include "slurm_cluster.h"

#include <arpa/inet.h>
#include <dirent.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "testing/temp_dir.h"

namespace radfarm::packaging::testing {
namespace {

namespace fs = std::filesystem;
using ::radfarm::testing::ReadFile;
using ::radfarm::testing::RunCommand;
using ::radfarm::testing::WaitUntil;

constexpr auto kStartTimeout = std::chrono::seconds(60);
constexpr auto kStopGrace = std::chrono::seconds(15);

const std::vector<std::string> kPrograms = {"munged", "munge",    "slurmctld", "slurmd", "sbatch",
                                            "squeue", "scontrol", "scancel",   "sinfo"};

// The program's path from PATH (and the sbin directories, which a user's PATH may lack); "" if
// it is not installed.
std::string FindProgram(const std::string& name) {
  std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  path += ":/usr/sbin:/sbin:/usr/bin:/bin";
  std::istringstream dirs(path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty()) continue;
    const std::string candidate = dir + "/" + name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

// A TCP port nobody listens on now, from the kernel's ephemeral range.
int FreePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof(address);
  int port = -1;
  if (bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0 &&
      getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    port = ntohs(address.sin_port);
  }
  close(fd);
  return port;
}

std::string ShortHostName() {
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) != 0) return "localhost";
  const std::string host(name);
  return host.substr(0, host.find('.'));
}

// Half of this machine's memory in MiB: the node's RealMemory, below what slurmd measures.
long HalfMemoryMiB() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? pages / 2 * (page / 1024) / 1024 : 1024;
}

// The parent's pid from /proc/PID/stat ("PID (COMM) STATE PPID ..."); -1 if it is gone.
pid_t ParentOf(pid_t pid) {
  const std::string stat = ReadFile("/proc/" + std::to_string(pid) + "/stat");
  const size_t comm_end = stat.rfind(')');
  if (comm_end == std::string::npos) return -1;
  std::istringstream fields(stat.substr(comm_end + 1));
  std::string state;
  pid_t parent = -1;
  fields >> state >> parent;
  return parent;
}

std::string Trim(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

}  // namespace

std::string SlurmCluster::MissingPrograms() {
  std::string missing;
  for (const std::string& program : kPrograms) {
    if (FindProgram(program).empty()) missing += (missing.empty() ? "" : " ") + program;
  }
  return missing;
}

SlurmCluster::SlurmCluster(std::string dir)
    : dir_(std::move(dir)),
      conf_(dir_ + "/slurm.conf"),
      node_(ShortHostName()),
      munge_socket_(dir_ + "/run/munge.socket") {}

SlurmCluster::~SlurmCluster() { Stop(); }

std::string SlurmCluster::WriteConfig() {
  const int controller_port = FreePort(), node_port = FreePort();
  if (controller_port < 0 || node_port < 0 || controller_port == node_port) {
    return "cannot find two free TCP ports";
  }
  std::ofstream conf(conf_);
  // The plugins are the ones that need no cgroups, systemd scopes or accounting database.
  conf << "ClusterName=radfarmtest\n"
       << "SlurmctldHost=" << node_ << "(127.0.0.1)\n"
       << "SlurmctldPort=" << controller_port << "\n"
       << "SlurmdPort=" << node_port << "\n"
       << "SlurmUser=root\nSlurmdUser=root\n"
       << "AuthType=auth/munge\nCredType=cred/munge\n"
       << "AuthInfo=socket=" << munge_socket_ << "\n"
       << "StateSaveLocation=" << dir_ << "/state\n"
       << "SlurmdSpoolDir=" << dir_ << "/spool\n"
       << "SlurmctldPidFile=" << dir_ << "/run/slurmctld.pid\n"
       << "SlurmdPidFile=" << dir_ << "/run/slurmd.pid\n"
       << "SlurmctldDebug=info\nSlurmdDebug=info\n"
       << "ProctrackType=proctrack/linuxproc\n"
       << "TaskPlugin=task/none\n"
       << "JobAcctGatherType=jobacct_gather/none\n"
       << "AccountingStorageType=accounting_storage/none\n"
       << "JobCompType=jobcomp/none\n"
       << "MpiDefault=none\n"
       << "SelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n"
       << "SchedulerType=sched/builtin\n"
       << "ReturnToService=2\n"
       // The node as configured, whatever slurmd measures (fewer cores must not drain it).
       << "SlurmdParameters=config_overrides\n"
       << "NodeName=" << node_ << " NodeAddr=127.0.0.1 CPUs=2 RealMemory=" << HalfMemoryMiB()
       << " State=UNKNOWN\n"
       << "PartitionName=radfarm Nodes=ALL Default=YES MaxTime=INFINITE State=UP\n";
  return conf ? "" : "cannot write " + conf_;
}

std::string SlurmCluster::Start() {
  if (const std::string missing = MissingPrograms(); !missing.empty()) {
    return "not installed: " + missing + " (packages munge, slurm-wlm)";
  }
  std::error_code error;
  // munged insists that everyone may traverse to its socket, and that only its user may read
  // the key's directory.
  fs::permissions(dir_,
                  fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                      fs::perms::others_read | fs::perms::others_exec,
                  error);
  for (const char* sub : {"run", "state", "spool", "log", "munge"}) {
    fs::create_directories(dir_ + "/" + sub, error);
    if (error) return "cannot make " + dir_ + "/" + sub + ": " + error.message();
  }
  fs::permissions(dir_ + "/munge", fs::perms::owner_all, error);
  const std::string key = dir_ + "/munge/munge.key";
  const CommandResult made =
      RunCommand({"/bin/dd", "if=/dev/urandom", "of=" + key, "bs=1024", "count=1", "status=none"});
  if (made.exit_code != 0) return "cannot make a munge key: " + made.err;
  fs::permissions(key, fs::perms::owner_read, error);
  if (std::string written = WriteConfig(); !written.empty()) return written;

  started_ = true;
  munged_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{FindProgram("munged"), "--foreground", "--socket=" + munge_socket_,
                               "--key-file=" + key, "--pid-file=" + dir_ + "/run/munged.pid",
                               "--seed-file=" + dir_ + "/munge/munged.seed"},
      dir_ + "/log/munged.log");
  const std::string munge = FindProgram("munge");
  if (!WaitUntil(
          [&] {
            return RunCommand({munge, "--socket", munge_socket_, "--no-input"}).exit_code == 0;
          },
          kStartTimeout, std::chrono::milliseconds(100))) {
    return "munged did not start";
  }
  // Through env, so that the daemons and their job steps carry SLURM_CONF: Leftovers() finds
  // them by it.
  const std::string env = "SLURM_CONF=" + conf_;
  slurmctld_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{"/usr/bin/env", env, FindProgram("slurmctld"), "-D", "-f", conf_},
      dir_ + "/log/slurmctld.log");
  slurmd_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{"/usr/bin/env", env, FindProgram("slurmd"), "-D", "-f", conf_, "-N",
                               node_},
      dir_ + "/log/slurmd.log");
  std::string state;
  if (!WaitUntil(
          [&] {
            if (!slurmctld_->running() || !slurmd_->running()) return true;
            state = Trim(Client({"sinfo", "--noheader", "--nodes", node_, "--format", "%T"}).out);
            return state == "idle";
          },
          kStartTimeout, std::chrono::milliseconds(200)) ||
      state != "idle") {
    return "the node did not become idle (state '" + state + "')";
  }
  return "";
}

CommandResult SlurmCluster::Client(const std::vector<std::string>& args,
                                   const std::vector<std::string>& env) const {
  std::vector<std::string> command = args;
  if (!command.empty() && command[0].find('/') == std::string::npos) {
    command[0] = FindProgram(command[0]);
  }
  std::vector<std::string> changes = env;
  changes.push_back("SLURM_CONF=" + conf_);
  return RunCommand(command, changes);
}

void SlurmCluster::Stop() {
  if (!started_) return;
  started_ = false;
  if (slurmctld_ && slurmctld_->running()) {
    Client({"scancel", "--partition", "radfarm"});
    WaitUntil(
        [&] {
          return Trim(Client({"squeue", "--noheader"}).out).empty();
        },
        kStopGrace, std::chrono::milliseconds(200));
  }
  for (std::unique_ptr<ChildProcess>* daemon : {&slurmd_, &slurmctld_, &munged_}) {
    if (*daemon && (*daemon)->running()) (*daemon)->Stop(kStopGrace);
  }
  for (pid_t pid : ClusterProcesses()) kill(pid, SIGKILL);
}

std::vector<pid_t> SlurmCluster::ClusterProcesses() const {
  const std::string marker = "SLURM_CONF=" + conf_;
  std::vector<pid_t> found;
  DIR* proc = opendir("/proc");
  if (proc == nullptr) return found;
  while (const dirent* entry = readdir(proc)) {
    const pid_t pid = static_cast<pid_t>(std::atoi(entry->d_name));
    if (pid <= 0 || pid == getpid()) continue;
    std::istringstream environ(ReadFile("/proc/" + std::to_string(pid) + "/environ"));
    for (std::string variable; std::getline(environ, variable, '\0');) {
      if (variable == marker) {
        found.push_back(pid);
        break;
      }
    }
  }
  closedir(proc);
  return found;
}

std::vector<std::string> SlurmCluster::Leftovers() const {
  std::vector<std::string> leftovers;
  const pid_t controller = slurmctld_ ? slurmctld_->pid() : -1;
  for (pid_t pid : ClusterProcesses()) {
    bool daemon = false;
    for (const auto* process : {&slurmctld_, &slurmd_, &munged_}) {
      daemon = daemon || (*process && (*process)->pid() == pid);
    }
    // slurmctld's own helper (slurmscriptd) runs as long as it does; jobs run under slurmd.
    if (daemon || (controller > 0 && ParentOf(pid) == controller)) continue;
    std::string command = ReadFile("/proc/" + std::to_string(pid) + "/cmdline");
    for (char& c : command) c = c == '\0' ? ' ' : c;
    leftovers.push_back(std::to_string(pid) + " " + command);
  }
  return leftovers;
}

std::string SlurmCluster::Logs() const {
  std::string logs;
  for (const char* name : {"munged", "slurmctld", "slurmd"}) {
    logs += std::string("==== ") + name + "\n" + ReadFile(dir_ + "/log/" + name + ".log");
  }
  return logs;
}

}  // namespace radfarm::packaging::testing
