#!/usr/bin/env bash
# Regenerates every corpus file under corpora/ from Debian packages:
#   hershey-fonts-data (Hershey stroke fonts), gnuplot-nox (HP-GL plots),
#   fonts-dejavu-core, fonts-liberation2 and fonts-urw-base35 (glyph outlines),
#   libfreetype-dev (rendering), adwaita-icon-theme, librsvg2-bin and netpbm
#   (icons rasterized to binary images).
# Needs a built stepzip (build/stepzip) for the stepping of vectors.
# Usage: corpora/tools/regenerate.sh [path/to/stepzip]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
stepzip=${1:-$root/build/stepzip}
out=$root/corpora
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

apt_need=(hershey-fonts-data gnuplot-nox fonts-dejavu-core fonts-liberation2 fonts-urw-base35 adwaita-icon-theme
          librsvg2-bin netpbm libfreetype-dev pkg-config g++)
for p in "${apt_need[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || {
    echo "missing Debian package: $p (apt-get install ${apt_need[*]})" >&2; exit 1; }
done

g++ -O2 -std=c++20 "$here/trace_glyphs.cpp" $(pkg-config --cflags --libs freetype2) -o "$tmp/trace_glyphs"
g++ -O2 -std=c++20 "$here/trace_pbm.cpp" -o "$tmp/trace_pbm"
g++ -O2 -std=c++20 -I"$root/include" "$here/stepper_stream.cpp" "$root"/src/core/*.cpp \
    "$root/src/interpolate/linear.cpp" "$root/src/interpolate/segment.cpp" -o "$tmp/stepper_stream"

hershey=/usr/share/hershey-fonts
dejavu=/usr/share/fonts/truetype/dejavu
mkdir -p "$out/plotter" "$out/glyphs" "$out/stepper" "$out/random" "$out/traced"

# Plotter streams: a Hershey specimen sheet and gnuplot's HP-GL plots,
# stepped by each profile's own interpolator.
python3 "$here/hershey_gcode.py" 5 $hershey/futural.jhf $hershey/rowmant.jhf \
    $hershey/scripts.jhf $hershey/gothiceng.jhf $hershey/cyrillic.jhf $hershey/greek.jhf \
    > "$tmp/hershey.gcode"
(cd "$tmp" && gnuplot "$here/gnuplot_plots.gp")
cp "$tmp/plots.hpgl" "$out/plotter/gnuplot.hpgl"
for p in grbl marlin eval8 eval4 patent; do
  "$stepzip" interpolate --profile $p "$tmp/hershey.gcode" -o "$out/plotter/hershey-$p.fc" -f
done
for p in grbl eval4; do
  "$stepzip" interpolate --profile $p "$out/plotter/gnuplot.hpgl" -o "$out/plotter/gnuplot-$p.fc" -f
done

# Digitizer-like contours: glyph outlines rendered by FreeType and traced.
for c in 8 4; do
  : > "$out/glyphs/dejavu-$c.fc"
  for f in DejaVuSans DejaVuSerif DejaVuSansMono; do
    for px in 16 32 64; do
      "$tmp/trace_glyphs" $dejavu/$f.ttf $px $c 33 255 | sed "s|$dejavu/||" >> "$out/glyphs/dejavu-$c.fc"
    done
  done
done

# Contours of another family and other sizes: Liberation Serif and Sans Bold
# Italic at 24, 48 and 96 px, ASCII only.
liberation=/usr/share/fonts/truetype/liberation2
for c in 8 4; do
  : > "$out/glyphs/liberation-$c.fc"
  for f in LiberationSerif-Regular LiberationSans-BoldItalic; do
    for px in 24 48 96; do
      "$tmp/trace_glyphs" $liberation/$f.ttf $px $c 33 126 | sed "s|$liberation/||" >> "$out/glyphs/liberation-$c.fc"
    done
  done
done

# The same page of text in four Hershey fonts that share glyphs, every page
# at the same place.
python3 "$here/hershey_pages.py" 2 $hershey/futural.jhf $hershey/rowmans.jhf $hershey/meteorology.jhf \
    $hershey/greek.jhf > "$tmp/pages.gcode"
"$stepzip" interpolate --profile grbl "$tmp/pages.gcode" -o "$out/plotter/hershey-pages-grbl.fc" -f

# Large glyphs of a third family: C059 Roman at 256 px, capitals traced
# 8-connected, small letters 4-connected.
urw=/usr/share/fonts/opentype/urw-base35
"$tmp/trace_glyphs" $urw/C059-Roman.otf 256 8 65 90 | sed "s|$urw/||" > "$out/glyphs/c059-8.fc"
"$tmp/trace_glyphs" $urw/C059-Roman.otf 256 4 97 122 | sed "s|$urw/||" > "$out/glyphs/c059-4.fc"

# Binary images that are not glyphs, by another tracer: the Adwaita
# theme's symbolic icons of two categories at 64 and 160 px.
for c in 8 4; do
  "$here/icon_contours.sh" "$tmp/trace_pbm" $c "64 160" "places emblems" > "$out/traced/icons-$c.fc"
done

# A four-axis stepper stream (X, Y, Z, A) of an engraving job.
python3 "$here/engrave_path.py" 5 $hershey/futural.jhf $hershey/scripts.jhf > "$tmp/path.txt"
"$tmp/stepper_stream" < "$tmp/path.txt" > "$out/stepper/engrave-4axis.steps"

# Timed STEP/DIR logs (idle ticks included) from a trapezoid planner.
mkdir -p "$out/timed"
python3 "$here/timed_stream.py" --shapes 2 --seed 3 --tick-us 30 --moves "$out/timed/trapezoid-2axis.moves" \
    > "$out/timed/trapezoid-2axis.steps"
python3 "$here/timed_stream.py" --axes 3 --shapes 3 --seed 11 --steps-mm 160 160 400 \
    --rate 4000 4000 1200 --accel 300 300 100 --jd 0.01 --tick-us 40 --segment-ms 8 \
    --cpu-mhz 20 --moves "$out/timed/trapezoid-3axis.moves" > "$out/timed/trapezoid-3axis.steps"
# Held out: never used to choose a parameter of the timed models (docs/benchmarks.md).
python3 "$here/timed_stream.py" --shapes 1 --seed 27 --tick-us 40 --scurve > "$out/timed/heldout-scurve.steps"
python3 "$here/timed_stream.py" --shapes 1 --seed 25 --tick-us 50 --amass-levels 0 --rate 4000 4000 \
    --accel 300 300 > "$out/timed/heldout-noamass.steps"
python3 "$here/timed_stream.py" --axes 3 --shapes 1 --seed 26 --tick-us 50 --pipeline --segment-ms 5 \
    > "$out/timed/heldout-pipeline-3axis.steps"
python3 "$here/timed_stream.py" --axes 3 --shapes 1 --seed 31 --steps-mm 100 100 400 --rate 5000 5000 1500 \
    --accel 800 800 200 --tick-us 25 --segment-ms 6 --cpu-mhz 12 > "$out/timed/heldout-fast-3axis.steps"
# An excerpt of the Grbl 1.1h stream of ../shared/corpora-timed (beside the
# project): ticks 84663-89760, the job's G1 lines 38-41, whose moves (in
# steps at 100 steps/mm) are grbl-excerpt.moves.
shared=$root/../shared/corpora-timed
if [ -f "$shared/grbl_hershey.steps.xz" ]; then
  xz -dc "$shared/grbl_hershey.steps.xz" > "$tmp/grbl.steps"
  head -c 89761 "$tmp/grbl.steps" | tail -c 5098 > "$out/timed/grbl-excerpt.steps"
  printf '24 -72\n47 -47\n48 -24\n71 0\n' > "$out/timed/grbl-excerpt.moves"
  # the stream's first 74 568 ticks (the job's first 15 moves) and the
  # job's settings and first 30 moves (the 15 and the look-ahead after them)
  head -c 74568 "$tmp/grbl.steps" > "$out/timed/grbl-start.steps"
  xz -dc "$shared/grbl_hershey.nc.xz" | head -n 43 > "$out/timed/grbl-start.nc"
else
  echo "regenerate.sh: $shared not found: corpora/timed/grbl-excerpt.* and grbl-start.* left as they are" >&2
fi

# The worst case: random walks.
python3 "$here/random_walk.py" 8 100000 1 > "$out/random/walk-8.fc"
python3 "$here/random_walk.py" 4 100000 2 > "$out/random/walk-4.fc"

ls -l "$out"/*/
