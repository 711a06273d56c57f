#!/usr/bin/env bash
# Traced binary images that are not glyphs: the symbolic icons of the Adwaita
# icon theme (Debian adwaita-icon-theme, SVG), rasterized by rsvg-convert at
# each size, thresholded on their alpha channel at one half (netpbm), and
# traced by trace_pbm (8- or 4-connected, column-major starts).
# Usage: icon_contours.sh TRACE_PBM CONN SIZES CATEGORIES > out.fc
#   e.g. icon_contours.sh /tmp/trace_pbm 8 "96 192" "places devices"
# Icons are taken in sorted order of their paths.
set -euo pipefail
trace=$1 conn=$2 sizes=$3 categories=$4
theme=/usr/share/icons/Adwaita/scalable
for p in adwaita-icon-theme librsvg2-bin netpbm; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || {
    echo "icon_contours.sh: missing Debian package: $p" >&2; exit 1; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0
for size in $sizes; do
  for c in $categories; do
    for svg in $(find "$theme/$c" -name '*-symbolic.svg' | LC_ALL=C sort); do
      n=$((n + 1))
      rsvg-convert -w "$size" -h "$size" "$svg" | pngtopnm -alpha 2>/dev/null |
        pgmtopbm -threshold -value 0.5 | pnminvert > "$tmp/$(printf %05d $n).pbm"
    done
  done
done
"$trace" "$conn" "$tmp"/*.pbm
