#!/usr/bin/env bash
# Writes the several-MB inputs of docs/benchmarks.md ("The default level
# against xz -9e") into OUTDIR; nothing here is committed. Each is of an
# origin that corpora/ holds only a small sample of:
#   icons-big-8.fc, icons-big-4.fc  every symbolic icon of the Adwaita theme
#       at 128, 256 and 512 px, traced by trace_pbm (icon_contours.sh);
#   urw-big-8.fc, urw-big-4.fc  characters 33-126 of URW Bookman Light,
#       P052 Roman, URW Gothic Book, Z003 Medium Italic and Nimbus Sans Bold
#       at 128 and 256 px (Debian fonts-urw-base35), traced by trace_glyphs;
#   pages-big-grbl.fc, pages-big-eval8.fc  hershey_pages.py at 10 steps per
#       font unit with the Hershey fonts gothgbt, gothiceng, rowmant, timesrb,
#       futuram, rowmand, cursive, scripts (pairs that share glyphs), stepped
#       by `stepzip interpolate --profile grbl|eval8`.
#   glyphs-big.fc  the 8-connected glyph contours of docs/benchmarks.md's
#       "Fast tier" (Liberation and FreeFont faces at 96-384 px, characters
#       33-255; Debian fonts-liberation2, fonts-freefont-ttf), 3712211 bytes.
# Usage: corpora/tools/bench_inputs.sh STEPZIP OUTDIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
stepzip=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
out=$2
for p in fonts-urw-base35 fonts-liberation2 fonts-freefont-ttf hershey-fonts-data libfreetype-dev pkg-config g++ \
    adwaita-icon-theme librsvg2-bin netpbm; do  # (the last three: icon_contours.sh)
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || {
    echo "bench_inputs.sh: missing Debian package: $p" >&2; exit 1; }
done
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
g++ -O2 -std=c++20 "$here/trace_glyphs.cpp" $(pkg-config --cflags --libs freetype2) -o "$tmp/trace_glyphs"
g++ -O2 -std=c++20 "$here/trace_pbm.cpp" -o "$tmp/trace_pbm"

for c in 8 4; do
  "$here/icon_contours.sh" "$tmp/trace_pbm" $c "128 256 512" \
    "actions apps categories devices emblems emotes legacy mimetypes places status ui" > "$out/icons-big-$c.fc"
done

urw=/usr/share/fonts/opentype/urw-base35
for c in 8 4; do
  : > "$out/urw-big-$c.fc"
  for f in URWBookman-Light P052-Roman URWGothic-Book Z003-MediumItalic NimbusSans-Bold; do
    for px in 128 256; do
      "$tmp/trace_glyphs" $urw/$f.otf $px $c 33 126 | sed "s|$urw/||" >> "$out/urw-big-$c.fc"
    done
  done
done

# the comment lines keep the fonts' full paths, as when the figures of
# docs/benchmarks.md were measured
lib=/usr/share/fonts/truetype/liberation2 free=/usr/share/fonts/truetype/freefont
{
  for f in $lib/LiberationSans-Regular $lib/LiberationSerif-Regular $lib/LiberationMono-Regular \
           $free/FreeSans $free/FreeSerif; do
    for px in 96 160; do "$tmp/trace_glyphs" $f.ttf $px 8 33 255; done
  done
  for f in $lib/LiberationSans-Bold $lib/LiberationSans-Italic $lib/LiberationSerif-Italic \
           $free/FreeSerifBold $free/FreeSansOblique $free/FreeMono; do
    for px in 256 384; do "$tmp/trace_glyphs" $f.ttf $px 8 33 255; done
  done
} > "$out/glyphs-big.fc"

h=/usr/share/hershey-fonts
python3 "$here/hershey_pages.py" 10 $h/gothgbt.jhf $h/gothiceng.jhf $h/rowmant.jhf $h/timesrb.jhf \
  $h/futuram.jhf $h/rowmand.jhf $h/cursive.jhf $h/scripts.jhf > "$tmp/pages.gcode"
for p in grbl eval8; do
  "$stepzip" interpolate --profile $p "$tmp/pages.gcode" -o "$out/pages-big-$p.fc" -f
done
ls -l "$out"
