#!/usr/bin/env bash
# G-code out of `stepzip segment`: absolute and relative coordinates read
# back by `stepzip interpolate`, steps and millimetres, and F words from the
# feed-rate block (--feed V, steps per second; docs/cli.md).
# Usage: bash gcode.sh <stepzip-binary> <source-dir> [python3]
set -u
BIN=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
PY=${3:-python3}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Lines drawn by eval8 at its default phase, each turning away from the last,
# so `segment` finds them again one by one and the round trip is exact.
printf 'G0 X0 Y0\nG1 X7 Y3\nG1 X7 Y10\nG1 X-5 Y10\nG0 X20 Y20\nG1 X9 Y1\n' >lines.gcode
"$BIN" interpolate --profile eval8 lines.gcode >lines.fc || fail "interpolate lines"
for mode in absolute relative; do
    opt=""
    [ $mode = relative ] && opt=--relative
    "$BIN" segment lines.fc --profile eval8 --to gcode $opt >$mode.gcode || fail "$mode: segment"
    want=G90
    [ $mode = relative ] && want=G91
    grep -qx "$want" $mode.gcode || fail "$mode: no $want line"
    [ "$(grep -c '^G0' $mode.gcode)" -eq 2 ] || fail "$mode: expected 2 G0 moves"
    [ "$(grep -c '^G1' $mode.gcode)" -eq 4 ] || fail "$mode: expected 4 G1 moves: $(cat $mode.gcode)"
    "$BIN" interpolate --profile eval8 $mode.gcode >$mode.fc || fail "$mode: interpolate back"
    cmp -s lines.fc $mode.fc || fail "$mode: chains differ after the round trip"
done
grep -qx 'G1 X-12 Y0' relative.gcode || fail "relative: no 'G1 X-12 Y0': $(cat relative.gcode)"

# Millimetres: 0.0125 mm per step, read back at the same step size.
"$BIN" segment lines.fc --profile eval8 --to gcode --step-size 0.0125 >mm.gcode || fail "mm"
grep -qx 'G21' mm.gcode || fail "mm: no G21"
grep -qx 'G1 X0.0875 Y0.0375' mm.gcode || fail "mm: first move not X0.0875 Y0.0375: $(cat mm.gcode)"
"$BIN" interpolate --profile eval8 --step-size 0.0125 mm.gcode >mm.fc || fail "mm: interpolate"
cmp -s lines.fc mm.fc || fail "mm: chains differ after the round trip"

# Feed words. A run of 10 steps at 100 steps/s: 10 steps in 0.1 s, F6000.
feed() { grep -o 'F[0-9.]*' "$1" | tr '\n' ' ' | sed 's/ $//'; }
echo '0 0 0000000000' >run.fc
"$BIN" segment run.fc --to gcode --feed 100 >run.gcode || fail "feed run"
grep -qx 'G94' run.gcode || fail "feed: no G94"
[ "$(feed run.gcode)" = "F6000" ] || fail "feed run: '$(feed run.gcode)', expected F6000"
"$BIN" segment run.fc --to gcode --feed 100 --step-size 0.01 >run-mm.gcode || fail "feed mm"
[ "$(feed run-mm.gcode)" = "F60" ] || fail "feed mm: '$(feed run-mm.gcode)', expected F60 (mm/min)"
# A diagonal of 4 steps: stamps 1, 1+1.41, 1+2x1.41, 1+3x1.41 ticks of 0.01 s
# (seed 000's factor), or sqrt(2) with --feed-factor exact.
echo '0 0 1111' >diag.fc
for factor in seed exact; do
    "$BIN" segment diag.fc --to gcode --feed 100 --feed-factor $factor >diag.gcode \
        || fail "feed diag $factor"
    want=$($PY -c "
import math
k = 1.41 if '$factor' == 'seed' else math.sqrt(2)
print('F%.3f' % (60 * 4 * math.sqrt(2) / (0.01 * (1 + 3 * k))))")
    [ "$(feed diag.gcode)" = "$want" ] || fail "feed diag $factor: '$(feed diag.gcode)', expected $want"
done
# F is modal: two runs at the same speed carry one F word.
echo '0 0 0000022222' >two.fc
"$BIN" segment two.fc --to gcode --profile eval8 --feed 50 >two.gcode || fail "feed modal"
[ "$(feed two.gcode)" = "F3000" ] || fail "feed modal: '$(feed two.gcode)', expected one F3000"
[ "$(grep -c '^G1' two.gcode)" -eq 2 ] || fail "feed modal: expected 2 moves"
# The G-code with F words reads back to the same chains (F is ignored).
"$BIN" segment lines.fc --profile eval8 --to gcode --feed 250 >fed.gcode || fail "feed lines"
"$BIN" interpolate --profile eval8 fed.gcode >fed.fc || fail "feed: interpolate back"
cmp -s lines.fc fed.fc || fail "feed: chains differ after the round trip"
# Usage errors: exit 2.
for bad in "--feed 0" "--feed -3" "--feed fast" "--feed 10 --feed-factor odd"; do
    "$BIN" segment run.fc --to gcode $bad >/dev/null 2>&1
    [ $? -eq 2 ] || fail "'$bad' should be a usage error"
done
"$BIN" segment run.fc --to hpgl --feed 10 >/dev/null 2>&1
[ $? -eq 2 ] || fail "--feed with --to hpgl should be a usage error"

if [ "$failures" -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "gcode: all checks passed"
