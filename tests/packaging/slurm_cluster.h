// SlurmCluster: a one-node Slurm cluster on this machine for tests, from Debian's munge and
// slurm-wlm: munged, slurmctld and slurmd, each in the foreground as a child process, with a
// scratch munge key and a minimal slurm.conf (one node, this host at 127.0.0.1, 2 CPUs; free
// ports; every state, spool, pid and log file in the scratch directory). Plugins are the ones that
// work in a container: proctrack/linuxproc, task/none, no cgroup, accounting or MPI plugins.
//
// Slurm's clients (sbatch, squeue, scontrol) find the cluster through SLURM_CONF, which Start()
// sets in this process's environment, so the daemons, their job steps and the clients run by
// Client() all use it; the destructor restores it. Jobs run as the caller, who must be root (slurmd
// runs its job steps as the submitting user).
//
// Teardown (Stop(), or the destructor): every job cancelled, the daemons stopped with SIGTERM
// (SIGKILL after a grace period), then any process left that belongs to the cluster (a job step,
// a program a job started: found by SLURM_CONF in its environment) killed. Leftovers() lists
// them first, so a test can assert that its jobs ended by themselves.
//
//   SlurmCluster slurm(dir);
//   ASSERT_EQ(slurm.Start(), "") << slurm.Logs();
//   CommandResult submitted = slurm.Client({"sbatch", "--parsable", "job.sh"});
#pragma once

#include <sys/types.h>

#include <memory>
#include <string>
#include <vector>

#include "testing/child_process.h"

namespace radfarm::packaging::testing {

using ::radfarm::testing::ChildProcess;
using ::radfarm::testing::CommandResult;

class SlurmCluster {
 public:
  // The programs the cluster needs that are not installed, space-separated; "" when all are.
  static std::string MissingPrograms();

  // `dir` must exist; the cluster keeps every file there.
  explicit SlurmCluster(std::string dir);
  ~SlurmCluster();
  SlurmCluster(const SlurmCluster&) = delete;
  SlurmCluster& operator=(const SlurmCluster&) = delete;

  // Starts munged, slurmctld and slurmd and waits until the node is idle. "" on success, else
  // what failed (the daemons' logs are in Logs()).
  std::string Start();
  // Runs a Slurm client command (sbatch, squeue, ...) against this cluster; `env` as
  // RunCommand's env_changes ("NAME=value"), which sbatch passes on to the job.
  CommandResult Client(const std::vector<std::string>& args,
                       const std::vector<std::string>& env = {}) const;
  // Cancels every job, waits for the queue to empty and stops the daemons; idempotent.
  void Stop();
  // Processes that belong to the cluster other than its three daemons (pid and command line).
  std::vector<std::string> Leftovers() const;
  // The daemons' logs.
  std::string Logs() const;

  const std::string& node() const { return node_; }
  const std::string& conf() const { return conf_; }

 private:
  std::string WriteConfig();
  std::vector<pid_t> ClusterProcesses() const;

  std::string dir_, conf_, node_, munge_socket_;
  std::string saved_slurm_conf_;
  bool had_slurm_conf_ = false;
  bool started_ = false;
  std::unique_ptr<ChildProcess> munged_, slurmctld_, slurmd_;
};

}  // namespace radfarm::packaging::testing
