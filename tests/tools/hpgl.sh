#!/usr/bin/env bash
# HP-GL with real tools as judges: hp2xx draws what `stepzip segment --to hpgl`
# writes without a warning; HP-GL written by gnuplot's hpgl terminal (the
# corpus file, and one made here when gnuplot is installed) goes through
# `stepzip interpolate` and back through `stepzip segment --to hpgl` with no
# more pen-down vertices than gnuplot wrote, and the chains survive the trip.
# Usage: bash hpgl.sh <stepzip-binary> <source-dir> [python3]
# Exit 77 (skipped) when hp2xx is not installed.
set -u
BIN=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
PY=${3:-python3}
COUNT="$PY $SRC/tests/tools/hpgl_count.py"
if ! command -v hp2xx >/dev/null; then
    echo "SKIP: hp2xx is not installed (Debian package hp2xx; scripts/setup-deps installs it)"
    exit 77
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
    local name=$1 hpgl=$2 profile=$3 segmenter=$4
    "$BIN" interpolate --profile "$profile" "$hpgl" >"$name.fc" 2>"$name.err" \
        || { fail "$name: interpolate: $(cat "$name.err")"; return; }
    "$BIN" segment "$name.fc" --profile "$profile" --segmenter "$segmenter" --to hpgl \
        >"$name.hpgl" 2>"$name.err" || { fail "$name: segment: $(cat "$name.err")"; return; }
    hp2xx_clean "$name" "$name.hpgl"
    read -r _ v_in _ p_in < <($COUNT "$hpgl")
    read -r _ v_out _ p_out < <($COUNT "$name.hpgl")
    [ "$v_in" -gt 0 ] || fail "$name: no vertices counted in $hpgl"
    [ "$v_out" -le "$v_in" ] || fail "$name: $v_out pen-down vertices, gnuplot wrote $v_in"
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
    round_trip generated-eval8 plot.hpgl eval8 optimal
    round_trip generated-eval4 plot.hpgl eval4 greedy
else
    echo "note: gnuplot is not installed (Debian gnuplot-nox); only the corpus file is used"
fi

if [ "$failures" -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "hpgl: all checks passed"
