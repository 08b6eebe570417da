#!/usr/bin/env bash
# Renders the stills away from noon in docs/clouds.md ("Away from noon"): the default scene at
# sunset toward and away from the sun, in civil twilight, the peer's view backlit by a sun
# 12 degrees up, and the moonlit altocumulus, each at 320x180 as the renderer makes it (left)
# and with clouds.quality: reference (right), side by side in docs/images/clouds/stills/.
# Also re-renders the lighting images of docs/lighting.md (render-lighting-images.sh).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/build.sh" release skyrender >/dev/null
sky="$root/build/release/apps/skyrender/skyrender"
out="$root/docs/images/clouds/stills"
mkdir -p "$out"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
still() {  # name scene overrides...
  local name="$1" scene="$2"
  shift 2
  local sets=()
  for s in "$@"; do sets+=(--set "$s"); done
  "$sky" render "$root/configs/$scene" --out "$tmp" --name "$name" --width 320 --height 180 \
    "${sets[@]}" >/dev/null
  "$sky" render "$root/configs/$scene" --out "$tmp" --name "${name}_reference" --width 320 \
    --height 180 "${sets[@]}" --set clouds.quality=reference >/dev/null
  /usr/bin/python3 - "$tmp/$name.png" "$tmp/${name}_reference.png" "$out/$name.png" <<'EOF'
import sys
from PIL import Image
a, b = Image.open(sys.argv[1]), Image.open(sys.argv[2])
c = Image.new("RGB", (a.width + 4 + b.width, a.height), (255, 255, 255))
c.paste(a, (0, 0))
c.paste(b, (a.width + 4, 0))
c.save(sys.argv[3])
EOF
}
sunset=time=2024-06-21T21:25:00+02:00
still sunset_toward default.yaml "$sunset" camera.heading=305
still sunset_away default.yaml "$sunset" camera.heading=125
still civil_twilight default.yaml time=2024-06-21T21:55:00+02:00 camera.heading=305
still backlit examples/peer_view.yaml sun.azimuth=0 sun.elevation=12
still moonlit examples/altocumulus_moon.yaml
echo "wrote docs/images/clouds/stills/{sunset_toward,sunset_away,civil_twilight,backlit,moonlit}.png"
"$root/scripts/render-lighting-images.sh"
