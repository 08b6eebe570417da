#!/usr/bin/env bash
# Regenerates configs/stars/bright_star_catalogue.txt from the Yale Bright Star Catalogue
# (5th revised ed.) as shipped in Debian's xplanet package (/usr/share/xplanet/stars/BSC).
# Keeps only Dec, RA and V magnitude, in the package's order, copied as text (no rounding),
# so the output depends only on the package version.
#
#   scripts/import-star-catalogue.sh              # apt-get download xplanet (no root needed)
#   scripts/import-star-catalogue.sh FILE.deb     # use a .deb already at hand
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
out="$root/configs/stars/bright_star_catalogue.txt"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

if [ $# -ge 1 ]; then
  deb="$(realpath "$1")"
else
  # As root apt warns that it downloads unsandboxed (its _apt user cannot write here): harmless.
  (cd "$work" && apt-get download xplanet >/dev/null)
  deb="$(ls "$work"/xplanet_*.deb)"
fi
version="$(dpkg-deb -f "$deb" Version)"
dpkg-deb -x "$deb" "$work/pkg"
bsc="$work/pkg/usr/share/xplanet/stars/BSC"
[ -f "$bsc" ] || { echo "error: $deb has no usr/share/xplanet/stars/BSC" >&2; exit 1; }

{
  cat <<HEADER
# Yale Bright Star Catalogue, 5th revised edition (Hoffleit & Warren 1991, VizieR V/50),
# as distributed in Debian's xplanet package $version: /usr/share/xplanet/stars/BSC.
# Regenerate with scripts/import-star-catalogue.sh; see configs/stars/README.md.
# Equinox and epoch J2000. One star per line, the package's order (brightest first):
#   dec_deg  declination in degrees, [-90, 90]
#   ra_h     right ascension in hours, [0, 24)
#   vmag     visual (Johnson V) magnitude
# dec_deg ra_h vmag
HEADER
  # Data lines are "Dec RA Mag \"name\" BSN HD SAO"; comments start with '#'.
  LC_ALL=C awk '!/^[[:space:]]*#/ && NF >= 3 { print $1, $2, $3 }' "$bsc"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out ($(grep -vc '^#' "$out") stars)"
