#!/usr/bin/env bash
# SVG in, with rsvg-convert as judge:
# - steps -> `segment --to svg` -> `interpolate` gives the same steps, for
#   every profile that writes exact vectors;
# - an SVG with curves, arcs and nested transforms is stepped, and the steps
#   lie on rsvg-convert's raster of it and cover it (tests/tools/svg_raster.py,
#   2 pixels of slack: the 0.5-step tolerance, rounding to steps, the
#   stroke's half width and anti-aliasing).
# Usage: bash svg_in.sh <stepzip-binary> <source-dir> [python3]
# Exit 77 (skipped) when rsvg-convert is not installed. Every command's exit
# status is checked.
set -euo pipefail
BIN=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
PY=${3:-python3}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Round trips through the plain SVG that segment writes (no renderer needed).
printf '0 0 00000000002222222222\n20 5 66665555444433\n3 12 7\n-40 -7 0101001010010100101001010010\n' >chains.fc
"$BIN" interpolate --profile eval8 "$SRC/corpora/samples/plot.gcode" >plot.fc
for profile in eval8 grbl marlin; do
    for input in chains plot; do
        "$BIN" segment "$input.fc" --to svg --profile "$profile" -q >"$input.$profile.svg" 2>err \
            || { fail "$input/$profile: segment: $(cat err)"; continue; }
        "$BIN" interpolate --profile "$profile" "$input.$profile.svg" >"$input.$profile.fc" 2>err \
            || { fail "$input/$profile: interpolate: $(cat err)"; continue; }
        # 'segment' drops chains without steps: compare those that have some
        grep -v ' $' "$input.fc" | awk 'NF == 3' >want.fc
        cmp -s want.fc "$input.$profile.fc" || fail "$input/$profile: steps differ after the SVG round trip"
        echo "$input/$profile: round trip exact ($(wc -l <"$input.$profile.fc") chains)"
    done
done
# eval4 from 4-connected steps
"$BIN" interpolate --profile eval4 "$SRC/corpora/samples/plot.gcode" >plot4.fc
"$BIN" segment plot4.fc --to svg --profile eval4 -q >plot4.svg
"$BIN" interpolate --profile eval4 --from svg plot4.svg >plot4.back.fc
cmp -s plot4.fc plot4.back.fc || fail "plot/eval4 (4-connected): steps differ after the SVG round trip"

# A malformed file: one error line with file:line:column, no output file.
printf '<svg>\n<path d="M0 0 C1 2"/>\n</svg>\n' >bad.svg
if "$BIN" interpolate --profile eval8 bad.svg -o bad.fc 2>err; then
    fail "a malformed path was accepted"
else
    [ "$(cat err)" = "stepzip: bad.svg:2:16: missing or malformed arguments of 'C'" ] \
        || fail "malformed path: $(cat err)"
    [ ! -e bad.fc ] || fail "malformed path: an output file was left"
fi
"$BIN" interpolate --profile eval8 --tolerance 0 bad.svg >/dev/null 2>err && fail "--tolerance 0 accepted"
"$BIN" interpolate --profile eval8 --tolerance 1 "$SRC/corpora/samples/plot.gcode" >/dev/null 2>err \
    && fail "--tolerance accepted for G-code"

if ! command -v rsvg-convert >/dev/null; then
    echo "SKIP: rsvg-convert is not installed (Debian package librsvg2-bin; scripts/setup-deps installs it)"
    [ "$failures" -eq 0 ] || exit 1
    exit 77
fi
cat >pic.svg <<'SVG'
<?xml version="1.0" encoding="UTF-8"?>
<!-- curves, arcs and transforms; user units are pixels (viewBox = size) -->
<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 240 160" width="240" height="160">
  <g fill="none" stroke="#000" stroke-width="1">
    <path d="M10 150 C 10 60, 110 60, 110 100 S 210 140, 230 120"/>
    <path d="M20,20 q40-30 80,0t80,0"/>
    <path d="M130 40 a 40 20 30 1 0 60 30 A25 25 0 0 1 130 40z"/>
    <g transform="translate(60,100) rotate(-20)">
      <circle r="25"/>
      <g transform="scale(1.5,0.8) skewX(15)"><rect x="-10" y="-10" width="20" height="20" rx="4"/></g>
    </g>
    <ellipse cx="190" cy="110" rx="35" ry="15" transform="rotate(15 190 110)"/>
    <polyline points="5 5 30 12 5 30"/>
  </g>
</svg>
SVG
rsvg-convert -o pic.png pic.svg 2>err || fail "rsvg-convert: $(cat err)"
for profile in eval8 grbl eval4; do
    "$BIN" interpolate --profile "$profile" pic.svg >"pic.$profile.fc" 2>err \
        || { fail "pic/$profile: interpolate: $(cat err)"; continue; }
    got=$($PY "$SRC/tests/tools/svg_raster.py" pic.png "pic.$profile.fc" 2) \
        || fail "pic/$profile: steps off rsvg-convert's raster: $got"
    echo "pic/$profile: $got"
done
# The check can fail: the large arc on its other side is off the raster.
sed 's/a 40 20 30 1 0/a 40 20 30 1 1/' pic.svg >flipped.svg
"$BIN" interpolate --profile eval8 flipped.svg >flipped.fc
if $PY "$SRC/tests/tools/svg_raster.py" pic.png flipped.fc 2 >/dev/null; then
    fail "a wrongly swept arc matched the raster"
fi

if [ "$failures" -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "svg_in: all checks passed"
