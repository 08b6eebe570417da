#!/usr/bin/env bash
# The path-traced reference for the cloud lighting (issues 14 and 30, docs/cloud-model.md
# "Path-traced reference"): for each scene of configs/pathtrace/, renders it with skyrender,
# exports its cloud density in a box around the cloud (skyrender export-volume), renders our
# clear sky of the same scene as an equirectangular image for Cycles' world, renders the grid
# with Blender's Cycles under that world and our sun (render_cycles.py), then compares the two
# (compare.py): per-pixel luminance error, lit/shadowed ratio, the colour (blue/red) of the
# shadowed core and the silver rim over the core, written to $OUT/results.{json,md} and as
# side-by-side images in docs/images/pathtrace/.
# Not part of CI (Cycles takes minutes); CI's smoke test is tests/cloud_volume.
#
# Usage: scripts/pathtrace/compare.sh [SCENE...]   (default: all eight)
# Environment:
#   SKYRENDER  the skyrender binary (default: build/release/apps/skyrender/skyrender)
#   SAMPLES    Cycles samples per pixel (default 512); BOUNCES volume bounces (default 128)
#   SEED       Cycles' seed (default 1)
#   WORLD      sky (default): Cycles' world is our sky; constant: the palette's ambient_top
#              above the horizon and ambient_bottom below (the world before issue 30)
#   WORLD_AT   cloud (default): our sky as seen from the middle of the cloud layer (the
#              altitude the sun's light is taken at); camera: from the camera
#   SPLIT      scenes to render twice more in Cycles, with the sun alone and with the sky
#              alone, to split the cloud's light into sunlight and skylight (default: none)
#   OUT        working folder (default: out/pathtrace); IMAGES (default: docs/images/pathtrace)
#   NICE       the niceness Blender and skyrender run at (default 10: a shared machine)
#   VOXEL_M    the cumulus scenes' voxel size in metres (default 15: the raymarch's billows
#              are 50-200 m across; at 30 m side noon's error was a point higher)
set -euo pipefail
cd "$(dirname "$0")/../.."
./scripts/install-deps.sh --pathtracer

SKYRENDER="${SKYRENDER:-build/release/apps/skyrender/skyrender}"
SAMPLES="${SAMPLES:-512}"
BOUNCES="${BOUNCES:-128}"
SEED="${SEED:-1}"
WORLD="${WORLD:-sky}"
WORLD_AT="${WORLD_AT:-cloud}"
SPLIT=" ${SPLIT:-} "
OUT="${OUT:-out/pathtrace}"
IMAGES="${IMAGES:-docs/images/pathtrace}"
NICE="${NICE:-10}"
[ -x "$SKYRENDER" ] || { echo "error: $SKYRENDER: no such binary (build it: scripts/build.sh release skyrender, or set SKYRENDER)" >&2; exit 2; }
case "$WORLD" in sky|constant) ;; *) echo "error: WORLD=$WORLD (expected sky or constant)" >&2; exit 2 ;; esac
case "$WORLD_AT" in cloud|camera) ;; *) echo "error: WORLD_AT=$WORLD_AT (expected cloud or camera)" >&2; exit 2 ;; esac

# The box around each scene's cloud (metres east, north, up of the camera: minimum corner,
# then maximum) and the voxel size: the whole cloud, with a margin of a voxel or two, so the
# path tracer sees all of the field the raymarch sees.
declare -A BOX VOXEL
CUMULUS_BOX=-2000,4770,450,2000,8570,2550
for s in cumulus_side_noon cumulus_backlit cumulus_sun3_toward cumulus_sun3_away \
         cumulus_sun12_toward cumulus_sun12_away cumulus_sun12_toward_kozlov; do
  BOX[$s]=$CUMULUS_BOX; VOXEL[$s]=${VOXEL_M:-15}
done
BOX[stratocumulus_below]=-5000,-1500,450,5000,5500,1500; VOXEL[stratocumulus_below]=40
ALL=(cumulus_side_noon cumulus_backlit stratocumulus_below
     cumulus_sun3_toward cumulus_sun3_away cumulus_sun12_toward cumulus_sun12_away
     cumulus_sun12_toward_kozlov)

# Our clear sky for Cycles' world: the scene with no low, mid or high clouds and no sun or
# moon disc (the sun lamp carries the sun's light; the disc in the world too would count it
# twice), the ground below the horizon as the composite draws it. Heading 90 puts east (our
# +x, Blender's +x) at the image's centre, where Cycles' equirectangular mapping has it.
CLEAR=(--set weather.source=procedural --set weather.cover_low=0 --set weather.cover_mid=0
       --set high_clouds.cover=0 --set sun.disc_scale=0 --set moon.disc_scale=0)
WORLD_SIZE=(--set output.width=1024 --set output.height=512)

cycles() {  # cycles LOG ARGS...: Blender in the background, its log kept
  local log="$1"; shift
  nice -n "$NICE" blender -b --factory-startup --python scripts/pathtrace/render_cycles.py -- "$@" \
    > "$log" 2>&1 || { tail -20 "$log" >&2; echo "error: Cycles failed (log: $log)" >&2; exit 1; }
  grep '^wrote' "$log"
}

scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=("${ALL[@]}")
mkdir -p "$OUT"
for s in "${scenes[@]}"; do
  [ -n "${BOX[$s]:-}" ] || { echo "error: unknown scene '$s' (known: ${!BOX[*]})" >&2; exit 2; }
  scene="configs/pathtrace/$s.yaml"
  start=$(date +%s)
  nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "$s"
  nice -n "$NICE" "$SKYRENDER" export-volume "$scene" --box "${BOX[$s]}" --voxel-m "${VOXEL[$s]}" --out "$OUT/$s.vdb"
  world=()
  if [ "$WORLD" = sky ]; then
    altitude=$(/usr/bin/python3 -c 'import sys, pyopenvdb
m = {g.name: g.metadata for g in pyopenvdb.readAllGridMetadata(sys.argv[1])}["density"]
print(m["light_altitude_m"] if sys.argv[2] == "cloud" else m["camera_altitude_m"])' "$OUT/$s.vdb" "$WORLD_AT")
    at=(--set "camera.altitude_m=$altitude")
    nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "${s}_world" "${CLEAR[@]}" "${at[@]}" \
      "${WORLD_SIZE[@]}" --set camera.projection=equirectangular --set camera.heading=90
    world=(--world "$OUT/${s}_world.exr")
    # The check of the world: Cycles looking at it through the scene's camera against
    # skyrender's own view of the same clear sky (compare.py reports the difference).
    nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "${s}_clear" "${CLEAR[@]}" "${at[@]}"
    cycles "$OUT/${s}_world_check.log" --vdb "$OUT/$s.vdb" --out "$OUT/${s}_world_check.exr" \
      "${world[@]}" --world-only --samples 16
  fi
  common=(--vdb "$OUT/$s.vdb" --samples "$SAMPLES" --bounces "$BOUNCES" --seed "$SEED" "${world[@]}")
  cycles "$OUT/${s}_cycles.log" "${common[@]}" --out "$OUT/${s}_cycles.exr"
  if [[ "$SPLIT" == *" $s "* ]]; then
    for lights in sun sky; do
      cycles "$OUT/${s}_cycles_$lights.log" "${common[@]}" --lights "$lights" --out "$OUT/${s}_cycles_$lights.exr"
    done
  fi
  echo "$s: $(( $(date +%s) - start )) s"
done
/usr/bin/python3 scripts/pathtrace/compare.py --dir "$OUT" --images "$IMAGES" "${scenes[@]}"
