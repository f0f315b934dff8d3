#!/bin/bash
# radfarm-agent as a Slurm batch job: the agent connects back to the master, renders on the cores
# Slurm gave it, and exits by itself after 5 minutes without work (or on SIGTERM at the time
# limit or on scancel, handing its leases back first). It needs no local state.
#
#   sbatch --array=1-20 radfarm-agent.slurm.sh      # twenty agents
#
# RADFARM_AGENT_CONF names a config on a shared file system, readable by you only, e.g.:
#   master = "radfarm-master.example.lan:7878"
#   secret_file = "/home/you/.config/radfarm/secret"    # mode 0600
#   [idle]
#   enabled = false      # Slurm already decided these cores are ours
#SBATCH --job-name=radfarm-agent
#SBATCH --cpus-per-task=16
#SBATCH --mem=8G
#SBATCH --time=08:00:00
#SBATCH --output=radfarm-agent-%A_%a.log
set -euo pipefail

conf=${RADFARM_AGENT_CONF:-$HOME/.config/radfarm/agent-batch.conf}
# exec: the agent itself receives Slurm's SIGTERM.
exec /usr/bin/radfarm-agent --config "$conf" \
  --threads "${SLURM_CPUS_PER_TASK:-1}" \
  --name "slurm-${SLURM_JOB_ID:-0}-${SLURM_ARRAY_TASK_ID:-0}" \
  --exit-when-idle 300
