#!/bin/sh
# verify_bench.sh: what exact validation (radfarmd --verify-fraction) costs a loopback farm. It
# solves the same job on radfarmd with two one-thread agents, alternating the fractions given, RUNS
# times each, and prints each run's wall time (submit to done), the master's count of verified
# batches and the CPU seconds the master and the agents used (utime + stime, /proc); every run's
# patches.csv must be byte-identical to the first.
#   [SUBMIT_FLAGS="--rays N"] bench/verify/verify_bench.sh BUILD_DIR [SCENE.toml] [RUNS] [FRACTIONS...]
# e.g. flock /tmp/radfarm-build.lock bench/verify/verify_bench.sh build scenes/cornell-box.toml 3 0 0.02 0.1
set -eu
build=$(cd "$1" && pwd); scene=$(realpath "${2:-scenes/cornell-box.toml}"); runs=${3:-3}
shift $(( $# < 3 ? $# : 3 ))
fractions=${*:-0 0.02}
work=$(mktemp -d); pids=""
trap '[ -z "$pids" ] || kill $pids 2>/dev/null; wait 2>/dev/null; rm -rf "$work"' EXIT
"$build/cli/radfarm" secret new "$work/secret" >/dev/null
run() {  # fraction, run number
  d="$work/$1-$2"; mkdir -p "$d"
  "$build/daemon/radfarmd" --listen 127.0.0.1:0 --state-dir "$d/master" --secret-file "$work/secret" \
    --verify-fraction "$1" --log-level info >"$d/master.log" 2>&1 &
  pids=$!; master=$!
  while [ ! -s "$d/master/listen.addr" ]; do sleep 0.05; done
  addr=$(cat "$d/master/listen.addr")
  for a in a b; do
    "$build/agent/radfarm-agent" --master "$addr" --secret-file "$work/secret" --threads 1 \
      --name "$a" --state-dir "$d/agent-$a" >"$d/agent-$a.log" 2>&1 &
    pids="$pids $!"
  done
  cli="$build/cli/radfarm --control $d/master/control.sock"
  while [ "$($cli agents --json | grep -c '"name"')" -lt 2 ]; do sleep 0.05; done
  start=$(date +%s.%N)
  id=$($cli submit "$scene" ${SUBMIT_FLAGS:-})
  while ! $cli status "$id" --json | grep -q '"state": *"done"'; do sleep 0.05; done
  end=$(date +%s.%N)
  $cli fetch "$id" --out "$d/out" >/dev/null
  verified=$(grep -o '[0-9]* batches verified so far' "$d/master.log" | tail -1 | cut -d' ' -f1)
  mismatches=$(grep -c 'verification failed' "$d/master.log" || true)
  ticks=$(getconf CLK_TCK)
  cpu() { awk -v t="$ticks" '{ s += ($14 + $15) / t } END { printf "%.2f", s }' "$@"; }
  master_cpu=$(cpu /proc/$master/stat)
  agent_cpu=$(for p in $pids; do [ "$p" = "$master" ] || echo /proc/$p/stat; done | xargs cat |
    awk -v t="$ticks" '{ s += ($14 + $15) / t } END { printf "%.2f", s }')
  printf '%s\t%s\t%.3f\t%s\t%s\t%s\t%s\n' "$1" "$2" "$(echo "$end - $start" | bc)" \
    "${verified:-0}" "$mismatches" "$master_cpu" "$agent_cpu"
  if [ -f "$work/reference.csv" ]; then
    cmp -s "$work/reference.csv" "$d/out/patches.csv" || echo "DIFFERENT patches.csv: $1 run $2"
  else
    cp "$d/out/patches.csv" "$work/reference.csv"
  fi
  kill $pids; wait 2>/dev/null || true; pids=""
}
printf 'fraction\trun\tseconds\tverified\tmismatches\tmaster_cpu_s\tagents_cpu_s\n'
for r in $(seq 1 "$runs"); do for f in $fractions; do run "$f" "$r"; done; done
