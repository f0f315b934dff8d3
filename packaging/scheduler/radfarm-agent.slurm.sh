#!/bin/bash
# radfarm-agent as a Slurm batch job: the agent connects back to the master, renders on the cores
# Slurm gave it, and exits by itself once it has held no lease for RADFARM_EXIT_WHEN_IDLE seconds,
# whether the master has no work or cannot be reached (or on SIGTERM at the time limit or on
# scancel, handing its leases back first). It needs no local state.
#
#   sbatch --array=1-20 radfarm-agent.slurm.sh                 # twenty agents
#   sbatch --array=1-4 --cpus-per-task=8 radfarm-agent.slurm.sh --log-level debug
#
# Arguments after the script's name go to radfarm-agent. sbatch passes your environment to the
# job, so these variables, set when you submit, configure it:
#   RADFARM_AGENT_CONF      the agent's config (default ~/.config/radfarm/agent-batch.conf)
#   RADFARM_AGENT           the program (default /usr/bin/radfarm-agent)
#   RADFARM_EXIT_WHEN_IDLE  seconds without a lease before the agent exits (default 300)
#
# The config lives on a shared file system, readable by you only (mode 0600), e.g.:
#   master = "radfarm-master.example.lan:7878"
#   secret_file = "/home/you/.config/radfarm/secret"    # mode 0600
#   [idle]
#   enabled = false      # Slurm already decided these cores are ours
#
# The #SBATCH lines below are defaults for a real node; options given to sbatch override them.
# tests/packaging/slurm_agents_test.cc runs this script under a one-node Slurm cluster.
#SBATCH --job-name=radfarm-agent
#SBATCH --cpus-per-task=16
#SBATCH --mem=8G
#SBATCH --time=08:00:00
#SBATCH --output=radfarm-agent-%A_%a.log
set -euo pipefail

conf=${RADFARM_AGENT_CONF:-$HOME/.config/radfarm/agent-batch.conf}
agent=${RADFARM_AGENT:-/usr/bin/radfarm-agent}
# The name says which array task this is (slurm-ARRAYJOB-TASK, as in the log's name); a plain
# job is slurm-JOB-0.
name="slurm-${SLURM_ARRAY_JOB_ID:-${SLURM_JOB_ID:-0}}-${SLURM_ARRAY_TASK_ID:-0}"
# exec: the agent itself receives Slurm's SIGTERM.
exec "$agent" --config "$conf" \
  --threads "${SLURM_CPUS_PER_TASK:-1}" \
  --name "$name" \
  --exit-when-idle "${RADFARM_EXIT_WHEN_IDLE:-300}" \
  "$@"
