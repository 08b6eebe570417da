#!/usr/bin/env bash
# Renders the four lighting images in docs/lighting.md (noon, sunset, end of civil twilight,
# full-moon midnight over Zurich, 21-22 June 2024) into docs/images/ at 320x180.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/build.sh" release skyrender >/dev/null
sky="$root/build/release/apps/skyrender/skyrender"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
render() {  # name time heading pitch fov
  "$sky" render --out "$tmp" --name "lighting_$1" --width 320 --height 180 --time "$2" \
    --set camera.heading="$3" --set camera.pitch="$4" --set camera.vertical_fov="$5" >/dev/null
  cp "$tmp/lighting_$1.png" "$root/docs/images/"
}
render noon 2024-06-21T13:30:00+02:00 180 30 80
render sunset 2024-06-21T21:25:00+02:00 305 10 60
render civil_twilight 2024-06-21T22:05:00+02:00 315 10 60
render full_moon_midnight 2024-06-22T00:30:00+02:00 165 15 60
echo "wrote docs/images/lighting_{noon,sunset,civil_twilight,full_moon_midnight}.png"
