#!/usr/bin/env bash
# The path-traced reference for the cloud lighting (issue 14, docs/cloud-model.md
# "Path-traced reference"): for each scene of configs/pathtrace/, renders it with skyrender,
# exports its cloud density in a box around the cloud (skyrender export-volume), renders that
# grid with Blender's Cycles (render_cycles.py), then compares the two (compare.py): mean
# relative luminance error over the cloud pixels and the lit/shadowed luminance ratio,
# written to $OUT/results.{json,md} and as side-by-side images in docs/images/pathtrace/.
# Not part of CI (Cycles takes minutes); CI's smoke test is tests/cloud_volume.
#
# Usage: scripts/pathtrace/compare.sh [SCENE...]   (default: all three)
# Environment:
#   SKYRENDER  the skyrender binary (default: build/release/apps/skyrender/skyrender)
#   SAMPLES    Cycles samples per pixel (default 256); BOUNCES volume bounces (default 128)
#   OUT        working folder (default: out/pathtrace); IMAGES (default: docs/images/pathtrace)
set -euo pipefail
cd "$(dirname "$0")/../.."
./scripts/install-deps.sh --pathtracer

SKYRENDER="${SKYRENDER:-build/release/apps/skyrender/skyrender}"
SAMPLES="${SAMPLES:-256}"
BOUNCES="${BOUNCES:-128}"
OUT="${OUT:-out/pathtrace}"
IMAGES="${IMAGES:-docs/images/pathtrace}"
[ -x "$SKYRENDER" ] || { echo "error: $SKYRENDER: no such binary (build it: scripts/build.sh release skyrender, or set SKYRENDER)" >&2; exit 2; }

# The box around each scene's cloud (metres east, north, up of the camera: minimum corner,
# then maximum) and the voxel size: the whole cloud, with a margin of a voxel or two, so the
# path tracer sees all of the field the raymarch sees.
declare -A BOX VOXEL
BOX[cumulus_side_noon]=-2000,4770,450,2000,8570,2550; VOXEL[cumulus_side_noon]=30
BOX[cumulus_backlit]=-2000,4770,450,2000,8570,2550;   VOXEL[cumulus_backlit]=30
BOX[stratocumulus_below]=-5000,-1500,450,5000,5500,1500; VOXEL[stratocumulus_below]=40

scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(cumulus_side_noon cumulus_backlit stratocumulus_below)
mkdir -p "$OUT"
for s in "${scenes[@]}"; do
  [ -n "${BOX[$s]:-}" ] || { echo "error: unknown scene '$s' (known: ${!BOX[*]})" >&2; exit 2; }
  scene="configs/pathtrace/$s.yaml"
  start=$(date +%s)
  "$SKYRENDER" render "$scene" --out "$OUT" --name "$s"
  "$SKYRENDER" export-volume "$scene" --box "${BOX[$s]}" --voxel-m "${VOXEL[$s]}" --out "$OUT/$s.vdb"
  blender -b --factory-startup --python scripts/pathtrace/render_cycles.py -- \
    --vdb "$OUT/$s.vdb" --out "$OUT/${s}_cycles.exr" --samples "$SAMPLES" --bounces "$BOUNCES" \
    > "$OUT/${s}_cycles.log" 2>&1 || { tail -20 "$OUT/${s}_cycles.log" >&2; echo "error: $s: Cycles failed (log: $OUT/${s}_cycles.log)" >&2; exit 1; }
  grep '^wrote' "$OUT/${s}_cycles.log"
  echo "$s: $(( $(date +%s) - start )) s"
done
/usr/bin/python3 scripts/pathtrace/compare.py --dir "$OUT" --images "$IMAGES" "${scenes[@]}"
