#!/usr/bin/env bash
# Renders the GFS perspective images in docs/weather.md ("The GFS clouds in perspective"):
# configs/examples/gfs_east_asia.yaml from 30 N 116 E on the ground and at 10 km, at local
# noon (04Z, the forecast's valid time through weather.time) and at dusk (09:30Z: 5.5 hours
# later, the clouds carried by the 500 hPa wind and evolved by the automaton), 480x270.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/build.sh" release skyrender >/dev/null
sky="$root/build/release/apps/skyrender/skyrender"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
render() {  # name time altitude pitch
  "$sky" render "$root/configs/examples/gfs_east_asia.yaml" --out "$tmp" --name "gfs_$1" \
    --time "$2" --set camera.altitude_m="$3" --set camera.pitch="$4" >/dev/null
  cp "$tmp/gfs_$1.png" "$root/docs/images/weather/"
}
render ground_noon 2011-01-15T04:00:00Z 50 8
render ground_dusk 2011-01-15T09:30:00Z 50 8
render 10km_noon 2011-01-15T04:00:00Z 10000 -5
render 10km_dusk 2011-01-15T09:30:00Z 10000 -5
echo "wrote docs/images/weather/gfs_{ground,10km}_{noon,dusk}.png"
