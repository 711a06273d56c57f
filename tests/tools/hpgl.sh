#!/usr/bin/env bash
# HP-GL with real tools as judges: hp2xx draws what `stepzip segment --to hpgl`
# writes without a warning; HP-GL written by gnuplot's hpgl terminal (the
# corpus file, and one made here when gnuplot is installed) goes through
# `stepzip interpolate` and back through `stepzip segment --to hpgl` with no
# more pen-down vertices than gnuplot wrote, and the chains survive the trip.
# The HP-GL test files that ship with hp2xx are read as hp2xx reads them:
# at least 35 of the 36 are stepped, what `segment --to hpgl` writes back is
# drawn by hp2xx without a warning, and hp2xx's raster of that matches its
# raster of the original (tests/tools/raster_compare.py).
# Usage: bash hpgl.sh <stepzip-binary> <source-dir> [python3]
# Fails when hp2xx or its test files are missing (scripts/setup-deps
# installs the Debian package hp2xx).
set -u
BIN=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
PY=${3:-python3}
COUNT="$PY $SRC/tests/tools/hpgl_count.py"
HP_TESTS=/usr/share/doc/hp2xx/hp-tests
if ! command -v hp2xx >/dev/null || [ ! -d "$HP_TESTS" ]; then
    echo "FAIL: hp2xx or $HP_TESTS is missing (Debian package hp2xx; scripts/setup-deps installs it)"
    exit 1
fi
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# hp2xx_clean NAME FILE: hp2xx converts FILE to PNG, reads every instruction
# and reports nothing ignored, nothing unexpected, no warning or error.
hp2xx_clean() {
    local name=$1 file=$2
    if ! hp2xx -m png -f "$name.png" "$file" >/dev/null 2>"$name.log"; then
        fail "$name: hp2xx failed: $(tail -3 "$name.log")"
        return
    fi
    grep -q 'HPGL command(s) ignored: 0$' "$name.log" \
        || fail "$name: hp2xx ignored commands: $(grep -i ignored "$name.log")"
    grep -Eq 'Unexpected event\(s\): +0$' "$name.log" \
        || fail "$name: hp2xx saw unexpected events: $(grep -i unexpected "$name.log")"
    if grep -Eiq 'warning|error|unknown|illegal' "$name.log"; then
        fail "$name: hp2xx complained: $(grep -Ei 'warning|error|unknown|illegal' "$name.log")"
    fi
    [ -s "$name.png" ] || fail "$name: hp2xx wrote no picture"
}

# round_trip NAME HPGL PROFILE SEGMENTER: HP-GL -> chains -> HP-GL, then the
# vertex count and the chains read back.
round_trip() {
    local name=$1 hpgl=$2 profile=$3 segmenter=$4 fewer=${5:-fewer}
    # labels are drawn by stepzip with its stroke font, by gnuplot's file as
    # text: they are left out so that the vertices compare
    $PY -c 'import re, sys; sys.stdout.write(re.sub(r"LB[^\x03]*\x03", "", open(sys.argv[1], encoding="latin-1").read()))' \
        "$hpgl" >"$name.in.hpgl"
    hpgl=$name.in.hpgl
    "$BIN" interpolate --profile "$profile" "$hpgl" >"$name.fc" 2>"$name.err" \
        || { fail "$name: interpolate: $(cat "$name.err")"; return; }
    "$BIN" segment "$name.fc" --profile "$profile" --segmenter "$segmenter" --to hpgl \
        >"$name.hpgl" 2>"$name.err" || { fail "$name: segment: $(cat "$name.err")"; return; }
    hp2xx_clean "$name" "$name.hpgl"
    read -r _ v_in _ p_in < <($COUNT "$hpgl")
    read -r _ v_out _ p_out < <($COUNT "$name.hpgl")
    [ "$v_in" -gt 0 ] || fail "$name: no vertices counted in $hpgl"
    if [ "$fewer" = fewer ]; then
        [ "$v_out" -le "$v_in" ] || fail "$name: $v_out pen-down vertices, gnuplot wrote $v_in"
    fi
    [ "$p_out" -le "$p_in" ] || fail "$name: $p_out paths, gnuplot wrote $p_in"
    # the vectors follow the chains: every vertex is a point of its chain, in
    # order, and interpolating them again gives chains with the same ends
    # (the steps in between are the same only where each segment has the
    # profile's default phase: a segment that merges two of gnuplot's lines
    # may not)
    "$BIN" interpolate --profile "$profile" "$name.hpgl" >"$name.back.fc" 2>"$name.err" \
        || fail "$name: interpolate of the output: $(cat "$name.err")"
    $PY "$SRC/tests/tools/chains_follow.py" "$name.fc" "$name.back.fc" "$name.hpgl" \
        >"$name.why" 2>&1 || fail "$name: $(cat "$name.why")"
    echo "$name: gnuplot $v_in vertices in $p_in paths, stepzip $v_out in $p_out"
}

# stepzip's own HP-GL, including relative-looking and single-step paths
printf '0 0 0000111122223333\n10 -5 7\n-3 4 66665555444\n' >own.fc
"$BIN" segment own.fc --to hpgl >own.hpgl || fail "own: segment failed"
hp2xx_clean own own.hpgl

corpus=$SRC/corpora/plotter/gnuplot.hpgl
for profile in eval8 eval4 grbl marlin; do
    round_trip "corpus-$profile-optimal" "$corpus" "$profile" optimal
done
round_trip corpus-eval8-greedy "$corpus" eval8 greedy

if command -v gnuplot >/dev/null; then
    gnuplot -e "set terminal hpgl; set output 'plot.hpgl'; set samples 400; \
                plot [0:10] sin(x)*exp(-x/5) title 'damped', x/10 - 0.5 title 'ramp'" \
        2>gnuplot.err || fail "gnuplot failed: $(cat gnuplot.err)"
    hp2xx -m png -f gnuplot.png plot.hpgl >/dev/null 2>&1 || fail "hp2xx cannot read gnuplot's file"
    # Smooth curves of 400 samples, scaled by SC to x3.36 / y6.336 and
    # rounded: the exact cut (default phases only, one segment of
    # look-ahead) is not minimal there and may write a few more vertices
    # than gnuplot did (about 5 % when last measured); the counts are shown,
    # the chains must survive.
    round_trip generated-eval8 plot.hpgl eval8 optimal any
    round_trip generated-eval4 plot.hpgl eval4 optimal any
else
    echo "note: gnuplot is not installed (Debian gnuplot-nox); only the corpus file is used"
fi

# hp2xx's own test files (some gzipped): PCL escapes, scaling, windows,
# arcs, circles, wedges, polygons, Beziers, labels, pens
stepped=0
total=0
for f in "$HP_TESTS"/*; do
    base=$(basename "$f" .gz)
    case $base in readme | *.eps) continue ;; esac
    total=$((total + 1))
    case $f in *.gz) gzip -dc "$f" >"$base" ;; *) cp "$f" "$base" ;; esac
    if ! "$BIN" interpolate --profile eval8 "$base" -o "$base.fc" 2>"$base.err"; then
        echo "not stepped: $(cat "$base.err")"
        continue
    fi
    stepped=$((stepped + 1))
    "$BIN" segment "$base.fc" --profile eval8 --to hpgl -q -o "$base.out.hpgl" 2>"$base.err" \
        || { fail "$base: segment: $(cat "$base.err")"; continue; }
    hp2xx_clean "$base" "$base.out.hpgl"
    "$BIN" interpolate --profile eval8 "$base.out.hpgl" -o "$base.back.fc" 2>"$base.err" \
        || fail "$base: reading our output: $(cat "$base.err")"
    cmp -s "$base.fc" "$base.back.fc" || fail "$base: the chains do not survive the trip"
done
echo "hp2xx test files: $stepped of $total stepped"
[ "$total" -eq 36 ] || fail "expected 36 HP-GL files in $HP_TESTS, found $total"
[ "$stepped" -ge 35 ] || fail "only $stepped of $total hp2xx test files stepped"
# the one refused: text that is no HP-GL ("X0=0;") in spectrum.plt
grep -q 'spectrum.plt:6:1: incomplete instruction' spectrum.plt.err \
    || fail "spectrum.plt: $(cat spectrum.plt.err)"
# Rasters: hp2xx draws the original and what segment wrote back (pens all
# black and 0.1 mm wide, plot size from the data); 99 % of each picture's ink
# lies within 2 pixels of the other's. Files whose rendering differs by
# design are left out: labels (hp2xx's font is not stepzip's), dashed line
# types (LT, UL: drawn solid), fills (FT, FP: outlines), several pages.
for base in arcs.hp at.hpg bz.hp ci.hp colors.hp ew.hpg acad.hp inter.hp la.hp miter.hp \
    win_1.hp 286x192.5_lq.hpg; do
    hp2xx -q -m pbm -N -p 11111111 -f "$base.a.pbm" "$base" >/dev/null 2>&1
    hp2xx -q -m pbm -N -p 11111111 -f "$base.b.pbm" "$base.out.hpgl" >/dev/null 2>&1
    got=$($PY "$SRC/tests/tools/raster_compare.py" "$base.a.pbm" "$base.b.pbm" 2 0.99) \
        || fail "$base: rasters differ: $got"
    echo "$base: $got"
done

if [ "$failures" -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "hpgl: all checks passed"
