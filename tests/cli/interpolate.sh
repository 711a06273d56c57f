#!/usr/bin/env bash
# stepzip interpolate: SPEC examples, stdin/stdout, -o, errors, exit codes and
# no partial output. Usage: bash interpolate.sh <stepzip-binary> <source-dir>
set -u
BIN=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_out NAME EXPECTED COMMAND... : stdout must equal EXPECTED, exit 0
expect_out() {
    local name=$1 expected=$2
    shift 2
    local got rc
    got=$("$@" 2>err.txt)
    rc=$?
    [ "$rc" -eq 0 ] || fail "$name: exit $rc ($(cat err.txt))"
    [ "$got" = "$expected" ] || fail "$name: got '$got', expected '$expected'"
}
# expect_err NAME CODE PATTERN COMMAND... : exit CODE, one stderr line matching PATTERN
expect_err() {
    local name=$1 code=$2 pattern=$3
    shift 3
    "$@" >out.txt 2>err.txt
    local rc=$?
    [ "$rc" -eq "$code" ] || fail "$name: exit $rc, expected $code ($(cat err.txt))"
    grep -q -- "$pattern" err.txt || fail "$name: stderr '$(cat err.txt)' lacks '$pattern'"
    [ "$(wc -l <err.txt)" -eq 1 ] || fail "$name: expected one stderr line, got: $(cat err.txt)"
}

# SPEC §6: G0 X0 Y0, G1 X7 Y3 under the patent profile
printf 'G0 X0 Y0\nG1 X7 Y3\n' >spec.gcode
expect_out "spec example (file)" "0 0 0020020020" "$BIN" interpolate --profile patent spec.gcode
expect_out "spec example (stdin)" "0 0 0020020020" \
    bash -c "'$BIN' interpolate --profile patent <spec.gcode"
expect_out "spec example (dash)" "0 0 0020020020" \
    bash -c "'$BIN' interpolate --profile patent - --from gcode <spec.gcode"
# the same drawing in HP-GL, detected from the content
expect_out "hpgl" "0 0 0020020020" \
    bash -c "printf 'IN;SP1;PU0,0;PD7,3;PU;' | '$BIN' interpolate --profile patent"
# eval4 (seed 000, F0 = 0) and eval8 on the same line
expect_out "eval4" "0 0 0200200200" "$BIN" interpolate --profile eval4 spec.gcode
expect_out "eval8" "0 0 0101010" "$BIN" interpolate --profile eval8 spec.gcode
# a 4-connected profile on a diagonal is a staircase
printf 'G1 X3 Y3\n' >diag.gcode
expect_out "eval4 diagonal" "0 0 020202" "$BIN" interpolate --profile eval4 diag.gcode
# G0 starts a new chain; relative moves
printf 'G0 X1 Y1\nG91 G1 X2\nG0 X5 Y0\nG1 Y-2\n' >two.gcode
expect_out "two chains" "$(printf '1 1 00\n8 1 66')" "$BIN" interpolate --profile eval4 two.gcode
# step size: 0.5 mm per step, 3.5 mm = 7 steps, 1.5 mm = 3 steps
printf 'G21 G1 X3.5 Y1.5\n' >mm.gcode
expect_out "step size" "0 0 0020020020" "$BIN" interpolate --profile patent --step-size 0.5 mm.gcode
# an arc: a quarter circle of radius 3, counter-clockwise, evaluation method
printf 'G0 X3 Y0\nG3 X0 Y3 I-3 J0\n' >arc.gcode
got=$("$BIN" interpolate --profile eval4 arc.gcode --to points | tail -n 1)
[ "$got" = "0 3" ] || fail "arc ends at (0, 3): got '$got'"
# points output
expect_out "points" "$(printf '0 0\n1 0\n1 1')" \
    bash -c "printf 'G1 X1 Y1\n' | '$BIN' interpolate --profile eval4 --to points"

# -o writes the file; an existing output is refused without -f
"$BIN" interpolate --profile patent spec.gcode -o out.fc || fail "-o: exit $?"
[ "$(cat out.fc)" = "0 0 0020020020" ] || fail "-o: content '$(cat out.fc)'"
expect_err "no overwrite" 1 "out.fc: already exists" "$BIN" interpolate --profile eval4 spec.gcode -o out.fc
[ "$(cat out.fc)" = "0 0 0020020020" ] || fail "refused overwrite changed the file"
"$BIN" interpolate --profile eval4 spec.gcode -o out.fc -f || fail "-f: exit $?"
[ "$(cat out.fc)" = "0 0 0200200200" ] || fail "-f: content '$(cat out.fc)'"
expect_out "-c wins over -o" "0 0 0200200200" "$BIN" interpolate --profile eval4 spec.gcode -c -o ignored.fc
[ ! -e ignored.fc ] || fail "-c still wrote the -o file"

# errors: one line naming file:line:column, exit 1, no output file, no temp left
printf 'G0 X0 Y0\nG1 X7 Y3\nG28\n' >bad.gcode
expect_err "unsupported word" 1 "^stepzip: bad.gcode:3:1: unsupported word 'G28'" \
    "$BIN" interpolate --profile eval4 bad.gcode -o bad.fc
[ ! -e bad.fc ] || fail "partial output left after an error"
printf 'G0 X0 Y0\nG1 X7.5 Y3\n' >frac.gcode
expect_err "not whole" 1 "frac.gcode:2:4: coordinate 7.5 is not a whole number of steps" \
    "$BIN" interpolate --profile eval4 frac.gcode -o frac.fc
printf 'IN;\nPD1,2,3;\n' >odd.plt
expect_err "hpgl odd" 1 "odd.plt:2:1: odd number of coordinates" "$BIN" interpolate --profile eval4 odd.plt
printf 'G0 X10 Y0\nG3 X0 Y13 I-10 J0\n' >offcircle.gcode
expect_err "arc off its circle" 1 "offcircle.gcode:2:1: " "$BIN" interpolate --profile eval4 offcircle.gcode
expect_err "missing input" 1 "nonexistent.gcode: " "$BIN" interpolate --profile eval4 nonexistent.gcode
printf 'hello\n' >hello.txt
expect_err "undetected" 1 "hello.txt: neither G-code, HP-GL nor SVG" "$BIN" interpolate --profile eval4 hello.txt
ls -A | grep -q '\.stepzip-' && fail "temporary file left behind: $(ls -A)"

# usage errors: exit 2
expect_err "no profile" 2 "--profile is required" "$BIN" interpolate spec.gcode
expect_err "bad profile" 2 "unknown profile 'nope'" "$BIN" interpolate --profile nope spec.gcode
expect_err "bad option" 2 "bogus" "$BIN" interpolate --profile eval4 --bogus spec.gcode
expect_err "bad step size" 2 "step size" "$BIN" interpolate --profile eval4 --step-size -1 spec.gcode
expect_err "bad arc method" 2 "unknown arc method" "$BIN" interpolate --profile eval4 --arc-method x spec.gcode

# the sample plot interpolates under every profile
for p in eval4 eval8 patent grbl marlin; do
    "$BIN" interpolate --profile "$p" "$SRC/corpora/samples/plot.gcode" -o "plot-$p.fc" \
        || fail "sample plot under $p"
done

# --axes: a slicer's G-code as a machine job, every move stepped
cat >print.gcode <<'GCODE'
; Slic3r-style start code
M107
M104 S200 ; set temperature
G28 ; home all axes
G1 Z5 F5000 ; lift nozzle
G21
G90
M82
G92 E0
G1 Z0.35 F7800
G1 E-2 F2400
G92 E0
G1 X10.5 Y10.2 F7800
G1 E2 F2400
G1 X20.125 Y10.2 E2.5
M83
G1 X20.125 Y20.3 E0.5
GCODE
"$BIN" interpolate --profile grbl --axes XYZE --steps-per-mm 80,80,400,93 print.gcode \
    --to steps -o print.steps -v 2>note.txt || fail "--axes: exit $?"
grep -q 'axes XYZE: 7 move(s) in 1 run(s), 6650 tick(s); 3 word(s) skipped' note.txt \
    || fail "--axes -v: $(cat note.txt)"
# one byte per tick of the leading axes: Z 2000 + 1860, E 186, X 840, E 186,
# X 770, Y 808 (E2.5 after G92 E0 at machine E -2 is 0.5 mm = 46.5 -> 47 steps)
[ "$(wc -c <print.steps)" -eq 6650 ] || fail "--axes: $(wc -c <print.steps) bytes"
got=$("$BIN" interpolate --profile grbl --axes XYZE --steps-per-mm 80,80,400,93 print.gcode \
    --to points | tail -n 1)
[ "$got" = "1610 1624 140 93" ] || fail "--axes end point: '$got'"
# the steps file reads back as one four-axis chain ending there
got=$("$BIN" segment print.steps --to json --profile grbl -q | grep -o '"start":\[[^]]*\],"steps":[0-9]*')
[ "$got" = '"start":[0,0,0,0],"steps":6650' ] || fail "--axes steps file: '$got'"
printf 'G1 X1 Y1\nG5 I1 J1 P1 Q1 X2 Y2\n' >spline.gcode
expect_err "motion word" 1 "spline.gcode:2:1: unsupported motion word 'G5'" \
    "$BIN" interpolate --profile grbl --axes XY spline.gcode
expect_err "spm without axes" 2 "--steps-per-mm needs --axes" \
    "$BIN" interpolate --profile grbl --steps-per-mm 80 spec.gcode
expect_err "bad axes" 2 "axes 'XQ'" "$BIN" interpolate --profile grbl --axes XQ spec.gcode
expect_err "eval4 on 4 axes" 1 "profile eval4 takes 2 axes" \
    "$BIN" interpolate --profile eval4 --axes XYZE --steps-per-mm 80 print.gcode
expect_err "spm count" 2 "3 values for 4 axes" \
    "$BIN" interpolate --profile grbl --axes XYZE --steps-per-mm 1,2,3 print.gcode

if [ "$failures" -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "interpolate: all passed"
