#!/usr/bin/env bash
# Renders the GFS perspective images in docs/weather.md ("The GFS clouds in perspective"):
# configs/examples/gfs_east_asia.yaml from 30 N 116 E on the ground and at 10 km, at local
# noon (04Z, the forecast's valid time through weather.time) and at dusk (09:30Z: 5.5 hours
# later, the clouds carried by the 500 hPa wind and evolved by the automaton), 480x270; and
# one at noon from the edge of the cloud band at 37.7 N 120.5 E, looking east into it.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/build.sh" release skyrender >/dev/null
sky="$root/build/release/apps/skyrender/skyrender"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
render() {  # name time altitude pitch [more --set options]
  local name="$1" time="$2" altitude="$3" pitch="$4"
  shift 4
  "$sky" render "$root/configs/examples/gfs_east_asia.yaml" --out "$tmp" --name "gfs_$name" \
    --time "$time" --set camera.altitude_m="$altitude" --set camera.pitch="$pitch" "$@" >/dev/null
  cp "$tmp/gfs_$name.png" "$root/docs/images/weather/"
}
render ground_noon 2011-01-15T04:00:00Z 50 8
render ground_dusk 2011-01-15T09:30:00Z 50 8
render 10km_noon 2011-01-15T04:00:00Z 10000 -5
render 10km_dusk 2011-01-15T09:30:00Z 10000 -5
render band_edge_noon 2011-01-15T04:00:00Z 50 12 --set camera.latitude=37.7 \
  --set camera.longitude=120.5 --set camera.heading=80
echo "wrote docs/images/weather/gfs_{ground,10km}_{noon,dusk}.png, gfs_band_edge_noon.png"
