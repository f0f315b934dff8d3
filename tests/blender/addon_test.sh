#!/usr/bin/env bash
# The Blender add-on end to end (ctest BlenderAddon.*): `radfarm blender-addon install` puts it in
# a scratch Blender user folder, then Blender in background mode enables it, models a room, bakes
# and checks the result (addon_bake.py).
#   addon_test.sh RADFARM RADFARMD AGENT WHERE RESULT OUT
# WHERE is LOCAL (radfarm render on this machine) or FARM: a farm on loopback (radfarmd and one
# agent, as README's "A farm on one machine"), started here and stopped on exit.
# Exits 77 (ctest: skipped) only when blender is not installed.
set -euo pipefail
radfarm=$1 radfarmd=$2 agent_program=$3 where=$4 result=$5 out=$6
if ! command -v blender >/dev/null; then
  echo "SKIPPED: blender is not installed (Debian package blender, with python3-numpy for its" \
       "glTF add-on; scripts/install-deps --tests installs both, so CI runs this test)"
  exit 77
fi
rm -rf "$out"
mkdir -p "$out"
# Blender's user folders in the scratch directory: the user's own are never read or written.
export BLENDER_USER_SCRIPTS=$out/scripts BLENDER_USER_CONFIG=$out/config
"$radfarm" blender-addon install

master="" agent="" control=()
stop_farm() {
  local status=$?
  [ -n "$agent" ] && kill "$agent" 2>/dev/null && wait "$agent" || true
  if [ -n "$master" ]; then
    kill "$master" 2>/dev/null || true
    tail --pid="$master" -f /dev/null  # the master is not our child: wait for it to close its store
  fi
  if [ "$status" -ne 0 ] && [ -n "$master" ]; then
    echo "--- master log:"; tail -n 20 "$out/farm/master.log"
    echo "--- agent log:"; tail -n 20 "$out/farm/agent.log"
  fi
}
trap stop_farm EXIT
if [ "$where" = FARM ]; then
  "$radfarm" secret new "$out/farm/secret" >/dev/null
  # --detach returns once the master listens; the agent finds it through listen.addr.
  master=$("$radfarmd" --detach --listen 127.0.0.1:0 --state-dir "$out/farm/master" \
    --secret-file "$out/farm/secret" 2>>"$out/farm/master.log")
  "$agent_program" --master-file "$out/farm/master/listen.addr" --secret-file "$out/farm/secret" \
    --threads 2 2>>"$out/farm/agent.log" &
  agent=$!
  control=("$out/farm/master/control.sock")
fi
set +e
blender -b --factory-startup --python-exit-code 1 \
  --python "$(dirname "$0")/addon_bake.py" -- "$where" "$result" "$out/bake" "${control[@]}" 2>&1 |
  grep -E '^(addon_bake|Info|Error|Traceback|  File|[A-Za-z]+Error)'
status=${PIPESTATUS[0]}
set -e
exit "$status"
