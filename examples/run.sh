#!/usr/bin/env bash
# Runs the example programs on small inputs and checks what they produce
# with the stepzip command.
# Usage: bash run.sh <plotter_driver> <capture_compressor> <stepzip> <source-dir>
set -u
abs() { echo "$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"; }
DRIVER=$(abs "$1") CAPTURE=$(abs "$2") BIN=$(abs "$3") SRC=$(cd "$4" && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# plotter_driver: the same pulses as `stepzip interpolate`
"$DRIVER" "$SRC/corpora/plotter/gnuplot.hpgl" driver.fc 2>driver.err || fail "driver: $(cat driver.err)"
cat driver.err
"$BIN" interpolate --profile eval8 "$SRC/corpora/plotter/gnuplot.hpgl" >cli.fc || fail "cli interpolate"
cmp -s driver.fc cli.fc || fail "driver output differs from stepzip interpolate"
"$DRIVER" "$SRC/corpora/plotter/gnuplot.hpgl" driver4.fc eval4 2>/dev/null || fail "driver eval4"
"$BIN" interpolate --profile eval4 "$SRC/corpora/plotter/gnuplot.hpgl" >cli4.fc
cmp -s driver4.fc cli4.fc || fail "driver eval4 output differs"
"$DRIVER" /nonexistent out.fc 2>/dev/null && fail "driver accepted a missing file"

# capture_compressor: a two-axis capture (a plot's pulses as a STEP/DIR log)
printf 'G0 X0 Y0\nG1 X40 Y17\nG1 X40 Y60\nG1 X-3 Y2\nG1 X0 Y0\n' >shape.gcode
"$BIN" interpolate --profile grbl --to steps shape.gcode -o capture.steps || fail "make capture"
"$CAPTURE" capture.stz <capture.steps >live.txt 2>capture.err || fail "capture: $(cat capture.err)"
cat capture.err
"$BIN" verify capture.stz capture.steps || fail "capture.stz does not verify"
[ "$(grep -c '^segment ' live.txt)" -ge 4 ] || fail "capture: expected at least 4 live segments: $(cat live.txt)"
# the live segments add up to the whole path (it ends where it started)
sum=$(awk '{x += $2; y += $3} END {print x, y}' live.txt)
[ "$sum" = "0 0" ] || fail "capture: live segments sum to $sum, expected 0 0"
# the 4-axis engraving log of the corpus
"$CAPTURE" engrave.stz 4 <"$SRC/corpora/stepper/engrave-4axis.steps" >live4.txt 2>capture4.err \
    || fail "capture 4 axes: $(cat capture4.err)"
"$BIN" verify engrave.stz "$SRC/corpora/stepper/engrave-4axis.steps" || fail "engrave.stz does not verify"

if [ "$failures" -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "examples: all checks passed"
