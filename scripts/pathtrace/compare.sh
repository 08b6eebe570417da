#!/usr/bin/env bash
# The path-traced reference for the cloud lighting (issues 14 and 30, docs/cloud-model.md
# "Path-traced reference"): for each scene of configs/pathtrace/, renders it with skyrender,
# exports its cloud density in a box around the cloud (skyrender export-volume), renders our
# clear sky of the same scene as an equirectangular image for Cycles' world, renders the grid
# with Blender's Cycles under that world and our sun (render_cycles.py), then compares the two
# (compare.py): per-pixel luminance error, lit/shadowed ratio, the colour (blue/red) of the
# shadowed core and the silver rim over the core, written to $OUT/results.{json,md} and as
# side-by-side images in docs/images/pathtrace/.
# The field_* scenes (issue 46, docs/cloud-model.md "A path-traced field") are a whole field
# of clouds to the horizon: exported as nested boxes whose voxels grow with distance
# (field_boxes.py, `export-volume --lod view`), rendered in Cycles twice, under our sky and
# under Blender's own Nishita sky, and compared on the final image, Cycles' clouds laid over
# our sky through our air in front (field_compare.py): the cloud-to-sky luminance ratio, the
# per-pixel error and the lit clouds' hue, and the two worlds' skies against ours.
# Not part of CI (Cycles takes minutes); CI's smoke test is tests/cloud_volume.
#
# Usage: scripts/pathtrace/compare.sh [SCENE...]   (default: all eight cumulus and deck
#        scenes; FIELD: the five field_* scenes)
# Environment:
#   SKYRENDER  the skyrender binary (default: build/release/apps/skyrender/skyrender)
#   SAMPLES    Cycles samples per pixel (default 512); BOUNCES volume bounces (default 128)
#   SEED       Cycles' seed (default 1)
#   SUN_PROFILE  layers (default): Cycles' sun takes the raymarch's light at each altitude
#              of the layer (sun_profile.py; the sun and the sky rendered apart and added,
#              about twice the time, the field's views 5-6 x); flat: the layer middle's light
#              everywhere (the reference before 2026-12-08)
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
#   SIZE       WxH: render every scene at this size instead of its own (e.g. 160x90 to try
#              the pipeline quickly); the field's voxels follow the pixel's size
#   FIELD_WORLDS  the field scenes' Cycles worlds, of "sky nishita" (default both)
#   FIELD_RANGE_KM, FIELD_SHELLS_KM, FIELD_MIN_VOXEL_M  the field's boxes (field_boxes.py;
#              defaults 100, 3,7,16,40 and 10)
#   FIELD_REFERENCE  write the field scenes' Cycles numbers to this JSON (the committed one is
#              tests/data/pathtrace/field_cycles.json, which tests/cloud_volume reads)
#   PEER       1: also measure the peer's four low-sun views (../shared/peers/takram) beside
#              ours on display-referred PNGs (peer_compare.py): ours rendered at 640x360 with
#              the README's flags through PEER_VIEW (default Un-tone-mapped), each against its
#              clear sky. PEER_RESULTS: the peer's images (default ../shared/peers/takram/
#              results); PEER_CLEAR: its clear skies, peer_clear_VIEW.png (default
#              configs/pathtrace/peer_clear; made with the peer's run.sh, COVERAGE=0 and the
#              view's EXTRA_QUERY, see there); PEER_OCIO: the OCIO config ours goes through
#              (default: skyrender's own)
set -euo pipefail
cd "$(dirname "$0")/../.."
./scripts/install-deps.sh --pathtracer

SKYRENDER="${SKYRENDER:-build/release/apps/skyrender/skyrender}"
SAMPLES="${SAMPLES:-512}"
BOUNCES="${BOUNCES:-128}"
SEED="${SEED:-1}"
SUN_PROFILE="${SUN_PROFILE:-layers}"
WORLD="${WORLD:-sky}"
WORLD_AT="${WORLD_AT:-cloud}"
SPLIT=" ${SPLIT:-} "
OUT="${OUT:-out/pathtrace}"
IMAGES="${IMAGES:-docs/images/pathtrace}"
NICE="${NICE:-10}"
[ -x "$SKYRENDER" ] || { echo "error: $SKYRENDER: no such binary (build it: scripts/build.sh release skyrender, or set SKYRENDER)" >&2; exit 2; }
case "$SUN_PROFILE" in layers|flat) ;; *) echo "error: SUN_PROFILE=$SUN_PROFILE (expected layers or flat)" >&2; exit 2 ;; esac
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
FIELD=(field_sun3_toward field_sun3_away field_sun12_toward field_sun60_away field_deck_sunset)
for s in "${FIELD[@]}"; do BOX[$s]=field; done
FIELD_WORLDS=" ${FIELD_WORLDS:-sky nishita} "
SIZE_SET=()
if [ -n "${SIZE:-}" ]; then
  [[ "$SIZE" =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "error: SIZE=$SIZE (expected WxH, e.g. 160x90)" >&2; exit 2; }
  SIZE_SET=(--set "output.width=${BASH_REMATCH[1]}" --set "output.height=${BASH_REMATCH[2]}")
fi

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

light_altitude() {  # light_altitude VDB cloud|camera: where our world is rendered from
  /usr/bin/python3 -c 'import sys, pyopenvdb
m = {g.name: g.metadata for g in pyopenvdb.readAllGridMetadata(sys.argv[1])}["density"]
print(m["light_altitude_m"] if sys.argv[2] == "cloud" else m["camera_altitude_m"])' "$1" "$2"
}

# A field scene: the clouds in view to the horizon, in nested boxes; Cycles under our sky and
# under Blender's Nishita sky; the air in front taken from a second render of ours.
field() {
  local s="$1" scene="configs/pathtrace/$1.yaml"
  nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "$s" "${SIZE_SET[@]}"
  # The same clouds with another light (no diffusion term): the beauty changes by the air's
  # transmittance times the change in the clouds' light, which gives field_compare.py the
  # air in front of each pixel's clouds (docs/cloud-model.md, "A path-traced field").
  nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "${s}_ms0" "${SIZE_SET[@]}" \
    --set clouds.multiple_scattering=0
  nice -n "$NICE" "$SKYRENDER" validate "$scene" "${SIZE_SET[@]}" > "$OUT/${s}_settings.yaml"
  local boxes
  boxes=$(/usr/bin/python3 scripts/pathtrace/field_boxes.py "$OUT/${s}_settings.yaml" \
    --range-km "${FIELD_RANGE_KM:-100}" --shells-km "${FIELD_SHELLS_KM:-3,7,16,40}" \
    --min-voxel-m "${FIELD_MIN_VOXEL_M:-10}")
  # shellcheck disable=SC2086  # the boxes are words
  nice -n "$NICE" "$SKYRENDER" export-volume "$scene" "${SIZE_SET[@]}" $boxes --out "$OUT/$s.vdb"
  # The clouds outside the view that stand between it and the sun, a file each (they do not
  # nest with the view's boxes): without them a 3 degree sun behind the camera lit the view's
  # clouds as if the sky toward it were clear past their near side (field_boxes.py --shadow).
  local shadow=() k=0 line
  rm -f "$OUT/${s}"_shadow_*.vdb
  while read -r line; do
    [ -n "$line" ] || continue
    # shellcheck disable=SC2086  # the box's words
    nice -n "$NICE" "$SKYRENDER" export-volume "$scene" "${SIZE_SET[@]}" $line --out "$OUT/${s}_shadow_$k.vdb"
    shadow+=(--vdb "$OUT/${s}_shadow_$k.vdb")
    k=$((k + 1))
  done < <(/usr/bin/python3 scripts/pathtrace/field_boxes.py "$OUT/${s}_settings.yaml" --shadow \
    --range-km "${FIELD_RANGE_KM:-100}" --shells-km "${FIELD_SHELLS_KM:-3,7,16,40}" \
    --min-voxel-m "${FIELD_MIN_VOXEL_M:-10}")
  local at=(--set "camera.altitude_m=$(light_altitude "$OUT/$s.vdb" "$WORLD_AT")")
  nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "${s}_world" "${CLEAR[@]}" "${at[@]}" \
    "${WORLD_SIZE[@]}" --set camera.projection=equirectangular --set camera.heading=90
  nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "${s}_clear" "${CLEAR[@]}" "${at[@]}" \
    "${SIZE_SET[@]}"
  local common=(--vdb "$OUT/$s.vdb" "${shadow[@]}" --samples "$SAMPLES" --bounces "$BOUNCES" --seed "$SEED"
                --sun-profile "$SUN_PROFILE")
  if [[ "$FIELD_WORLDS" == *" sky "* ]]; then
    cycles "$OUT/${s}_world_check.log" --vdb "$OUT/$s.vdb" --out "$OUT/${s}_world_check.exr" \
      --world "$OUT/${s}_world.exr" --world-only --samples 16
    cycles "$OUT/${s}_cycles.log" "${common[@]}" --world "$OUT/${s}_world.exr" --out "$OUT/${s}_cycles.exr"
  fi
  if [[ "$FIELD_WORLDS" == *" nishita "* ]]; then
    cycles "$OUT/${s}_nishita_check.log" --vdb "$OUT/$s.vdb" --out "$OUT/${s}_nishita_check.exr" \
      --nishita --world-only --samples 16
    cycles "$OUT/${s}_cycles_nishita.log" "${common[@]}" --nishita --out "$OUT/${s}_cycles_nishita.exr"
  fi
}

scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || [ "${PEER:-0}" = 1 ] || scenes=("${ALL[@]}")
mkdir -p "$OUT"
for s in "${scenes[@]}"; do
  [ -n "${BOX[$s]:-}" ] || { echo "error: unknown scene '$s' (known: ${!BOX[*]})" >&2; exit 2; }
  scene="configs/pathtrace/$s.yaml"
  start=$(date +%s)
  if [ "${BOX[$s]}" = field ]; then
    field "$s"
    echo "$s: $(( $(date +%s) - start )) s"
    continue
  fi
  nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "$s" "${SIZE_SET[@]}"
  nice -n "$NICE" "$SKYRENDER" export-volume "$scene" "${SIZE_SET[@]}" --box "${BOX[$s]}" --voxel-m "${VOXEL[$s]}" --out "$OUT/$s.vdb"
  world=()
  if [ "$WORLD" = sky ]; then
    at=(--set "camera.altitude_m=$(light_altitude "$OUT/$s.vdb" "$WORLD_AT")")
    nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "${s}_world" "${CLEAR[@]}" "${at[@]}" \
      "${WORLD_SIZE[@]}" --set camera.projection=equirectangular --set camera.heading=90
    world=(--world "$OUT/${s}_world.exr")
    # The check of the world: Cycles looking at it through the scene's camera against
    # skyrender's own view of the same clear sky (compare.py reports the difference).
    nice -n "$NICE" "$SKYRENDER" render "$scene" --out "$OUT" --name "${s}_clear" "${CLEAR[@]}" "${at[@]}" \
      "${SIZE_SET[@]}"
    cycles "$OUT/${s}_world_check.log" --vdb "$OUT/$s.vdb" --out "$OUT/${s}_world_check.exr" \
      "${world[@]}" --world-only --samples 16
  fi
  common=(--vdb "$OUT/$s.vdb" --samples "$SAMPLES" --bounces "$BOUNCES" --seed "$SEED" "${world[@]}"
          --sun-profile "$SUN_PROFILE")
  cycles "$OUT/${s}_cycles.log" "${common[@]}" --out "$OUT/${s}_cycles.exr"
  if [[ "$SPLIT" == *" $s "* ]]; then
    for lights in sun sky; do
      cycles "$OUT/${s}_cycles_$lights.log" "${common[@]}" --lights "$lights" --out "$OUT/${s}_cycles_$lights.exr"
    done
  fi
  echo "$s: $(( $(date +%s) - start )) s"
done
if [ "${PEER:-0}" = 1 ]; then
  # The peer's view: the README's skyrender flags on the embedded default scene.
  PEER_FLAGS=(--set sky.model=physical --set camera.latitude=35 --set camera.longitude=139
    --set camera.altitude_m=10 --set camera.heading=0 --set camera.vertical_fov=60
    --set weather.cover_low=0.4 --set 'weather.region.lat=[32,38]' --set 'weather.region.lon=[136,142]'
    --set clouds.low.base_m=750 --set clouds.low.top_m=2200 --set high_clouds.cover=0.2
    --set output.width=640 --set output.height=360 --set "output.view=${PEER_VIEW:-Un-tone-mapped}")
  [ -z "${PEER_OCIO:-}" ] || PEER_FLAGS+=(--ocio "$PEER_OCIO")
  declare -A PEER_SUN=([toward]="3 0 10" [away]="3 180 10" [backlit]="12 0 20" [noon]="60 180 20")
  for v in toward away backlit noon; do
    read -r el az pitch <<< "${PEER_SUN[$v]}"
    view=(--set "sun.elevation=$el" --set "sun.azimuth=$az" --set "camera.pitch=$pitch")
    nice -n "$NICE" "$SKYRENDER" render --out "$OUT" --name "peer_$v" "${PEER_FLAGS[@]}" "${view[@]}"
    nice -n "$NICE" "$SKYRENDER" render --out "$OUT" --name "peer_${v}_clear" "${PEER_FLAGS[@]}" "${view[@]}" \
      --set weather.cover_low=0 --set high_clouds.cover=0
  done
  /usr/bin/python3 scripts/pathtrace/peer_compare.py --dir "$OUT" --images "$IMAGES" \
    --peer "${PEER_RESULTS:-../shared/peers/takram/results}" \
    --peer-clear "${PEER_CLEAR:-configs/pathtrace/peer_clear}" toward away backlit noon
fi
[ ${#scenes[@]} -gt 0 ] || exit 0
reference=()
[ -z "${FIELD_REFERENCE:-}" ] || reference=(--reference "$FIELD_REFERENCE" --samples "$SAMPLES" --sun-profile "$SUN_PROFILE")
/usr/bin/python3 scripts/pathtrace/compare.py --dir "$OUT" --images "$IMAGES" "${reference[@]}" "${scenes[@]}"
