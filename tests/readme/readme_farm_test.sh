#!/bin/bash
# Runs the shell blocks of README.md's "A farm on one machine" section (the farm, then its
# teardown) as they stand, in order, in one bash, in a scratch directory:
#   readme_farm_test.sh SOURCE_DIR BUILD_DIR
# The only changes to the README's text: /tmp/farm becomes SCRATCH/farm, so that two runs cannot
# meet. build/ and scenes/ are the README's own relative paths: the scratch directory holds links
# named build (to BUILD_DIR) and scenes (to SOURCE_DIR/scenes).
# Then it checks what the README promises: the job's files, fetched byte-identical to `radfarm
# render` (the golden SHA-256s of tests/cli/golden_render.sha256), and a teardown that leaves no
# process and no farm directory behind.
set -euo pipefail
source_dir=$(realpath "$1")
build_dir=$(realpath "$2")
readme="$source_dir/README.md"

scratch=$(mktemp -d /tmp/radfarm-readme.XXXXXX)
master="" agent=""
cleanup() {
  local status=$?
  if [ "$status" -ne 0 ]; then
    echo "--- failed (exit $status); master log:"; cat "$scratch/farm/master.log" 2>/dev/null || true
    echo "--- agent log:"; cat "$scratch/farm/agent.log" 2>/dev/null || true
  fi
  # Whatever the blocks left running when they failed.
  for pid in $agent $master; do kill -9 "$pid" 2>/dev/null || true; done
  rm -rf "$scratch"
}
trap cleanup EXIT

# The ```sh blocks between the section's heading and the next "## " heading.
awk '
  /^## / { inside = ($0 == "## A farm on one machine") }
  inside && /^```sh$/ { block = 1; next }
  inside && block && /^```$/ { block = 0; next }
  inside && block { print }
' "$readme" | sed "s|/tmp/farm|$scratch/farm|g" >"$scratch/blocks.sh"
echo "--- the README's commands, as run:"; cat "$scratch/blocks.sh"
# The farm, the status watch, the fetch and the teardown: at least that many commands.
[ "$(grep -c . "$scratch/blocks.sh")" -ge 8 ] || { echo "the README's farm section lost its blocks"; exit 1; }
grep -q 'rm -r' "$scratch/blocks.sh" || { echo "the README's farm section has no teardown"; exit 1; }

ln -s "$build_dir" "$scratch/build"
ln -s "$source_dir/scenes" "$scratch/scenes"
cd "$scratch"
# shellcheck disable=SC1091
source "$scratch/blocks.sh"

echo "--- checks"
for file in image.png image.exr radiosity.ply lit.glb patches.csv stats.json; do
  [ -s "out-farm/$file" ] || { echo "out-farm/$file is missing"; exit 1; }
done
for file in patches.csv image.exr radiosity.ply lit.glb; do
  want=$(awk -v f="cornell-box.toml/$file" '$2 == f { print $1 }' \
    "$source_dir/tests/cli/golden_render.sha256")
  got=$(sha256sum "out-farm/$file" | cut -d' ' -f1)
  [ "$want" = "$got" ] || { echo "out-farm/$file: SHA-256 $got, render's is $want"; exit 1; }
done
for pid in $agent $master; do
  if kill -0 "$pid" 2>/dev/null; then echo "process $pid still runs after the teardown"; exit 1; fi
done
[ ! -e "$scratch/farm" ] || { echo "the teardown left $scratch/farm"; exit 1; }
echo "the README's farm ran as written"
