#!/usr/bin/env bash
# One Blender round trip (ctest BlenderRoundTrip.*): radfarm renders SCENE into OUT, then Blender's
# own glTF importer reads OUT/lit.glb in background mode and check_lit_glb.py checks it.
#   round_trip.sh RADFARM SCENE OUT NAMES BRIGHTEST WALL_OBJECT WALL_MATERIAL PARENT [LIGHTMAPS]
# Exits 77 (ctest: skipped) only when blender is not installed.
set -euo pipefail
radfarm=$1 scene=$2 out=$3
shift 3
if ! command -v blender >/dev/null; then
  echo "SKIPPED: blender is not installed (Debian package blender, with python3-numpy for its" \
       "glTF add-on; scripts/install-deps --tests installs both, so CI runs this test)"
  exit 77
fi
rm -rf "$out"
"$radfarm" render "$scene" --out "$out" -q
# --factory-startup: no user preferences or add-ons; the glTF importer is enabled by default.
blender -b --factory-startup --python-exit-code 1 \
  --python "$(dirname "$0")/check_lit_glb.py" -- "$out/lit.glb" "$out/patches.csv" "$@" 2>&1 |
  grep -v '^$' | tail -n 5
exit "${PIPESTATUS[0]}"
