#include "testing/fault_campaign.h"

#include <signal.h>
#include <sys/mount.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include "testing/temp_dir.h"

namespace radfarm::testing {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// A tmpfs mounted over a directory for the campaign's life: a state directory that really fills.
class TmpfsMount {
 public:
  ~TmpfsMount() {
    if (mounted_) ::umount2(path_.c_str(), MNT_DETACH);
  }
  // Empty on success, else why not (mounting needs root or CAP_SYS_ADMIN).
  std::string Mount(const std::string& path, uint64_t bytes) {
    std::filesystem::create_directories(path);
    const std::string options = "size=" + std::to_string(bytes) + ",mode=0700";
    if (::mount("tmpfs", path.c_str(), "tmpfs", 0, options.c_str()) != 0) {
      return std::string("mount -t tmpfs: ") + std::strerror(errno);
    }
    path_ = path;
    mounted_ = true;
    return "";
  }
  bool mounted() const { return mounted_; }

 private:
  std::string path_;
  bool mounted_ = false;
};

// Waits `delay` on the clock: the campaign's schedule, not a synchronisation.
void Pause(milliseconds delay) {
  const auto until = Clock::now() + delay;
  WaitUntil([&] { return Clock::now() >= until; }, delay + std::chrono::seconds(1));
}

class Campaign {
 public:
  Campaign(const FarmPrograms& programs, const std::string& dir, const FaultPlan& plan,
           const std::string& reference, const std::function<void(const std::string&)>& say)
      : plan_(plan), reference_(reference), say_(say), random_(plan.seed), farm_(programs, dir) {}

  CampaignOutcome Run() {
    const auto start = Clock::now();
    if (Prepare()) {
      RunFaults();
      WaitForJobs();
      Check();
    }
    out_.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return out_;
  }

 private:
  int Random(int low, int high) { return std::uniform_int_distribution<int>(low, high)(random_); }
  void Problem(const std::string& text) {
    out_.problems.push_back(text);
    say_("PROBLEM: " + text);
  }

  // The state directory (mounted if disk fills are planned), a damaged store file refused, the
  // master up and every agent started.
  bool Prepare() {
    if (plan_.disk_fills > 0) {
      const std::string why = mount_.Mount(farm_.state_dir(), plan_.state_dir_bytes);
      if (!why.empty()) Problem("cannot give the state directory its own file system: " + why);
      if (!why.empty()) return false;
    }
    if (plan_.damage_store_at_start && !DamageStore()) return false;
    if (!StartMaster()) return false;
    for (unsigned i = 0; i < plan_.agents; ++i) {
      const std::string name = "a" + std::to_string(i);
      agents_.push_back({name, &farm_.StartAgent(name, 1)});
    }
    return true;
  }

  // Writes a damaged radfarm.db (empty, random bytes, or an SQLite header over random bytes),
  // checks that radfarmd refuses it naming the file, and moves it aside as an operator would.
  bool DamageStore() {
    std::filesystem::create_directories(farm_.state_dir());
    const std::string db = farm_.state_dir() + "/radfarm.db";
    const char* kinds[] = {"empty", "random bytes", "SQLite header over random bytes"};
    const int kind = Random(0, 2);
    std::string bytes = kind == 2 ? std::string("SQLite format 3\0", 16) : "";
    const int size = kind == 0 ? 0 : Random(1, 16) * 1024;
    while (int(bytes.size()) < size) bytes.push_back(char(Random(0, 255)));
    std::ofstream(db, std::ios::binary) << bytes;
    farm_.StartMaster(plan_.master_flags, std::chrono::seconds(60));
    const std::optional<int> exit = farm_.master()->WaitExit(std::chrono::seconds(60));
    std::string log = farm_.MasterLog();
    while (!log.empty() && log.back() == '\n') log.pop_back();
    say_(std::string("store damaged before start (") + kinds[kind] +
         "): " + log.substr(log.rfind('\n') + 1));
    ++out_.faults["store_damaged"];
    if (!exit || *exit == 0 || log.find("radfarm.db") == std::string::npos) {
      Problem(std::string("radfarmd did not refuse a store file of ") + kinds[kind] +
              " with a message naming it");
      return false;
    }
    std::filesystem::rename(db, db + ".damaged");
    return true;
  }

  // Starts (or restarts, on the same port) the master and waits for it to listen.
  bool StartMaster() {
    std::vector<std::string> flags = plan_.master_flags;
    if (!listen_.empty()) flags.insert(flags.end(), {"--listen", listen_});
    farm_.StartMaster(flags);
    if (farm_.master_address().empty() || !farm_.master()->running()) {
      Problem("radfarmd did not come up:\n" + farm_.MasterLog());
      return false;
    }
    listen_ = farm_.master_address();
    return true;
  }

  void Submit() {
    std::string error;
    const int64_t id = farm_.Submit(plan_.job_file, plan_.job_flags, &error);
    if (id < 0) return Problem(error);
    submitted_.push_back(id);
    ++out_.jobs_submitted;
    say_("submitted job " + std::to_string(id));
  }

  // Whether every job submitted so far has finished (or none was submitted).
  bool AllFinished() {
    for (int64_t id : submitted_) {
      if (!IsFinished(farm_.Status(id))) return false;
    }
    return true;
  }

  void RunFaults() {
    std::vector<std::string> schedule;
    schedule.insert(schedule.end(), size_t(plan_.agent_faults), "agent");
    schedule.insert(schedule.end(), size_t(plan_.master_kills), "master_kill");
    schedule.insert(schedule.end(), size_t(plan_.disk_fills), "disk_full");
    schedule.insert(schedule.end(), size_t(plan_.store_truncations), "store_truncated");
    std::shuffle(schedule.begin(), schedule.end(), random_);
    const size_t total = schedule.size();
    int next_job = 0;
    for (size_t i = 0; i < total; ++i) {
      while (next_job < plan_.jobs && size_t(next_job) * total / size_t(plan_.jobs) <= i) {
        Submit();
        ++next_job;
      }
      // Faults land while jobs run: when every job has finished, another is submitted.
      if (AllFinished()) Submit();
      const int gap = Random(0, int(plan_.max_gap.count()));
      Pause(milliseconds(gap));
      const std::string prefix = "fault " + std::to_string(i + 1) + "/" + std::to_string(total) +
                                 " after " + std::to_string(gap) + " ms: ";
      if (schedule[i] == "agent") AgentFault(prefix);
      if (schedule[i] == "master_kill" && !MasterKill(prefix)) return;
      if (schedule[i] == "disk_full") DiskFull(prefix);
      if (schedule[i] == "store_truncated" && !StoreTruncation(prefix)) return;
    }
    while (next_job++ < plan_.jobs) Submit();
  }

  void AgentFault(const std::string& prefix) {
    auto& [name, agent] = agents_[size_t(Random(0, int(agents_.size()) - 1))];
    const int kind = Random(0, 2);
    if (kind == 0) {
      agent->Signal(SIGKILL);
      agent->WaitExit(std::chrono::seconds(30));
      agent = &farm_.StartAgent(name, 1);
      ++out_.faults["agent_kill"];
      say_(prefix + "SIGKILL and restart agent " + name);
    } else if (kind == 1) {
      const int stopped = Random(0, int(plan_.max_stop.count()));
      agent->Signal(SIGSTOP);
      Pause(milliseconds(stopped));
      agent->Signal(SIGCONT);
      ++out_.faults["agent_stop"];
      say_(prefix + "SIGSTOP agent " + name + " for " + std::to_string(stopped) + " ms");
    } else {
      agent->Stop(std::chrono::seconds(10));
      agent = &farm_.StartAgent(name, 1);
      ++out_.faults["agent_restart"];
      say_(prefix + "SIGTERM and restart agent " + name);
    }
  }

  bool KillMaster() {
    farm_.master()->Signal(SIGKILL);
    if (farm_.master()->WaitExit(std::chrono::seconds(30))) return true;
    Problem("radfarmd did not die of SIGKILL");
    return false;
  }

  // Copies the store file and its WAL from `from` to `to` (paths of radfarm.db), replacing them.
  static void CopyStore(const std::string& from, const std::string& to) {
    for (const char* suffix : {"", "-wal"}) {
      std::filesystem::remove(to + suffix);
      if (std::filesystem::exists(from + suffix)) {
        std::filesystem::copy_file(from + suffix, to + suffix);
      }
    }
  }

  bool MasterKill(const std::string& prefix) {
    if (!KillMaster()) return false;
    ++out_.faults["master_kill"];
    say_(prefix + "SIGKILL and restart radfarmd");
    return StartMaster();
  }

  // SIGKILLs the master and cuts its store file short at a random byte, as a bad copy or a lost
  // write would. The restarted master must refuse the file naming it; then the copy taken before
  // is put back, as an operator restores a backup, and it starts again. If it comes up instead
  // (what was cut held no page the store needs, or the WAL still has them), no job may be lost
  // or changed: the final check says.
  bool StoreTruncation(const std::string& prefix) {
    if (!KillMaster()) return false;
    namespace fs = std::filesystem;
    const std::string db = farm_.state_dir() + "/radfarm.db";
    const std::string copy = farm_.File("store-copy");
    fs::create_directories(copy);
    CopyStore(db, copy + "/radfarm.db");
    const uintmax_t size = fs::file_size(db);
    const uintmax_t cut = std::uniform_int_distribution<uintmax_t>(0, size - 1)(random_);
    fs::resize_file(db, cut);
    const std::string what = prefix + "SIGKILL radfarmd, its store cut to " + std::to_string(cut) +
                             " of " + std::to_string(size) + " bytes: ";
    const size_t log_before = farm_.MasterLog().size();
    std::vector<std::string> flags = plan_.master_flags;
    flags.insert(flags.end(), {"--listen", listen_});
    farm_.StartMaster(flags, std::chrono::seconds(60));
    ++out_.faults["store_truncated"];
    if (!farm_.master_address().empty() && farm_.master()->running()) {
      ++out_.faults["store_truncated_taken"];
      say_(what + "taken, every page still there");
      return true;
    }
    const std::optional<int> exit = farm_.master()->WaitExit(std::chrono::seconds(60));
    std::string log = farm_.MasterLog().substr(log_before);
    while (!log.empty() && log.back() == '\n') log.pop_back();
    say_(what + "refused (" + log.substr(log.rfind('\n') + 1) + "); restored from the copy");
    if (!exit || *exit == 0 || log.find("radfarm.db") == std::string::npos) {
      Problem("radfarmd neither took nor refused, naming it, a store file cut short: " + log);
      return false;
    }
    CopyStore(copy + "/radfarm.db", db);
    fs::remove(db + "-shm");
    return StartMaster();
  }

  // Fills the state directory to ENOSPC, waits until a job is held for it (or a random while,
  // if no write came), and frees the space: held jobs must resume by themselves.
  void DiskFull(const std::string& prefix) {
    if (!mount_.mounted()) return;
    const std::string filler = farm_.state_dir() + "/filler";
    {
      std::ofstream out(filler, std::ios::binary);
      const std::string chunk(1 << 16, '\0');
      while (out.write(chunk.data(), std::streamsize(chunk.size())) && out.flush()) {
      }
    }
    const int most = Random(200, 3000);
    const bool held = WaitUntil(
        [&] {
          for (int64_t id : submitted_) {
            if (farm_.Status(id).value("state", "") == "paused") return true;
          }
          return false;
        },
        milliseconds(most), milliseconds(50));
    std::filesystem::remove(filler);
    ++out_.faults["disk_full"];
    out_.faults["disk_full_held_a_job"] += held;
    say_(prefix + "state directory full" +
         (held ? ", a job held, " : " for " + std::to_string(most) + " ms, ") + "freed");
  }

  void WaitForJobs() {
    const auto deadline = Clock::now() + plan_.job_timeout;
    for (int64_t id : submitted_) {
      const auto left = std::chrono::duration_cast<milliseconds>(deadline - Clock::now());
      farm_.WaitForJob(id, IsFinished, std::max(left, milliseconds(1)), milliseconds(100));
    }
  }

  void Check() {
    const CommandResult list = farm_.Cli({"list", "--json"});
    const nlohmann::json jobs = nlohmann::json::parse(list.out, nullptr, false);
    if (list.exit_code != 0 || !jobs.is_array()) return Problem("radfarm list: " + list.err);
    std::map<int64_t, int> listed;
    for (const auto& job : jobs) ++listed[job.value("id", int64_t(-1))];
    out_.jobs_listed = int(jobs.size());
    const std::set<int64_t> submitted(submitted_.begin(), submitted_.end());
    for (const auto& [id, times] : listed) {
      if (times > 1 || !submitted.count(id)) {
        ++out_.duplicated;
        Problem("job " + std::to_string(id) + " listed " + std::to_string(times) +
                " times, submitted " + std::to_string(submitted.count(id)));
      }
    }
    for (int64_t id : submitted_) {
      if (!listed.count(id)) {
        ++out_.lost;
        Problem("job " + std::to_string(id) + " was submitted and is not listed");
        continue;
      }
      CheckJob(id);
    }
  }

  void CheckJob(int64_t id) {
    const nlohmann::json job = farm_.Status(id);
    const std::string state = job.is_object() ? job.value("state", "") : "";
    const std::string name = "job " + std::to_string(id);
    if (state == "failed" && job["error"].is_string() && !job["error"].get<std::string>().empty()) {
      ++out_.failed_with_message;
      say_(name + " failed: " + job["error"].get<std::string>());
    } else if (state == "done") {
      const std::string fetched = farm_.File("fetch-" + std::to_string(id));
      const CommandResult r = farm_.Fetch(id, fetched);
      if (r.exit_code == 0 && ReadFile(fetched + "/patches.csv") == reference_) {
        ++out_.byte_identical;
      } else {
        ++out_.wrong_bytes;
        Problem(name + " is done but its patches.csv differs from render's " + r.err);
      }
    } else {
      ++out_.unfinished;
      Problem(name + " ended the campaign '" + state + "' (" + job.dump() + ")");
    }
  }

  FaultPlan plan_;
  std::string reference_;
  std::function<void(const std::string&)> say_;
  std::mt19937 random_;
  CampaignOutcome out_;
  TmpfsMount mount_;  // declared before the farm: unmounted after its processes are gone
  LoopbackFarm farm_;
  std::string listen_;
  std::vector<std::pair<std::string, ChildProcess*>> agents_;
  std::vector<int64_t> submitted_;
};

}  // namespace

CampaignOutcome RunFaultCampaign(const FarmPrograms& programs, const std::string& dir,
                                 const FaultPlan& plan, const std::string& reference_patches,
                                 const std::function<void(const std::string&)>& say) {
  return Campaign(programs, dir, plan, reference_patches, say).Run();
}

}  // namespace radfarm::testing
