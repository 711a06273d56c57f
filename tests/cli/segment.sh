#!/usr/bin/env bash
# stepzip segment: SPEC examples, every output format, stdin/stdout, -o,
# errors, exit codes and no partial output. Every command's exit status is
# checked (a failed command is reported, never skipped over).
# Usage: bash segment.sh <stepzip-binary> <source-dir>
set -euo pipefail
BIN=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_err NAME CODE PATTERN COMMAND... : exit CODE, one stderr line matching PATTERN
expect_err() {
    local name=$1 code=$2 pattern=$3
    shift 3
    local rc=0
    "$@" >out.txt 2>err.txt || rc=$?
    [ "$rc" -eq "$code" ] || fail "$name: exit $rc, expected $code ($(cat err.txt))"
    grep -q -- "$pattern" err.txt || fail "$name: stderr '$(cat err.txt)' lacks '$pattern'"
    [ "$(wc -l <err.txt)" -eq 1 ] || fail "$name: expected one stderr line, got: $(cat err.txt)"
}

# SPEC §6: the Fig. 5 chain under the patent segmenter: the first move ends at X8 Y3
echo '0 0 02002002000' >fig5.fc
"$BIN" segment fig5.fc --segmenter patent --to gcode >fig5.gcode 2>note.txt || fail "fig5: exit $?"
first=$(grep -m1 '^G1' fig5.gcode || true)
[ "$first" = "G1 X8 Y3" ] || fail "fig5: first move '$first', expected 'G1 X8 Y3'"
grep -q '^G0 X0 Y0$' fig5.gcode || fail "fig5: no G0 to the chain start"
grep -q 'patent approximation mode: 1 segment(s) read out, 0 reproduce' note.txt \
    || fail "fig5: deviation not reported: $(cat note.txt)"
"$BIN" segment fig5.fc --segmenter patent --to gcode -q 2>note.txt >/dev/null || fail "fig5 -q: exit $?"
[ ! -s note.txt ] || fail "-q still printed: $(cat note.txt)"
# ... the same from stdin, and as JSON with the deviation statistics
got=$(echo '0 0 02002002000' | "$BIN" segment --segmenter patent --to json -q) || fail "patent json: exit $?"
grep -q '"exact":false' <<< "$got" || fail "patent json: not marked inexact: $got"
grep -q '"delta":\[8,3\]' <<< "$got" || fail "patent json: no (8,3) segment: $got"
grep -q '"patent_max_deviation":' <<< "$got" || fail "patent json: no deviation: $got"

# exact segmenters: the output vectors, interpolated again, give the chain back
echo '0 0 0020020020' >patent.fc
got=$("$BIN" segment patent.fc --profile patent --to gcode | "$BIN" interpolate --profile patent) \
    || fail "patent round trip: exit $?"
[ "$got" = "0 0 0020020020" ] || fail "patent round trip: '$got'"
"$BIN" segment patent.fc --profile patent --to json -o patent.json || fail "patent json: exit $?"
grep -q '"delta":\[7,3\]' patent.json || fail "patent profile: (7,3) is not one segment"
for p in eval4 patent; do
    "$BIN" interpolate --profile "$p" "$SRC/corpora/samples/plot.gcode" -o "plot-$p.fc" \
        || fail "interpolate plot.gcode under $p: exit $?"
done
for seg in greedy optimal; do
    for p in eval4 patent; do
        "$BIN" segment "plot-$p.fc" --segmenter "$seg" --profile "$p" --to json -o "plot-$p-$seg.json" \
            || fail "plot $p $seg: exit $?"
        grep -q "\"profile\":\"$p\",\"segmenter\":\"$seg\",\"exact\":true" "plot-$p-$seg.json" \
            || fail "plot $p $seg: json header"
    done
done
# a line drawn under a profile is one segment under that profile, so the
# G-code written back interpolates to the same chains
"$BIN" interpolate --profile eval8 "$SRC/corpora/samples/plot.gcode" -o plot8.fc || fail "plot8: exit $?"
printf 'G0 X0 Y0\nG1 X40 Y17\nG1 X-3 Y5\n' | "$BIN" interpolate --profile eval8 -o lines.fc \
    || fail "lines.fc: exit $?"
"$BIN" segment lines.fc --profile eval8 --to gcode -o lines.gcode || fail "lines: exit $?"
[ "$(grep -c '^G1' lines.gcode)" -eq 2 ] || fail "lines: expected two G1 moves: $(cat lines.gcode)"
"$BIN" interpolate --profile eval8 lines.gcode -o lines2.fc || fail "lines2: exit $?"
cmp -s lines.fc lines2.fc || fail "lines: gcode round trip differs"
# HP-GL and relative G-code round trips
"$BIN" segment lines.fc --profile eval8 --to hpgl -o lines.plt || fail "hpgl: exit $?"
grep -q '^PD40,17,' lines.plt || fail "hpgl: content $(cat lines.plt)"
"$BIN" interpolate --profile eval8 lines.plt -o lines3.fc || fail "lines3: exit $?"
cmp -s lines.fc lines3.fc || fail "lines: hpgl round trip differs"
"$BIN" segment lines.fc --profile eval8 --to gcode --relative >rel.gcode || fail "--relative: exit $?"
grep -q '^G91$' rel.gcode || fail "--relative"
"$BIN" segment lines.fc --profile eval8 --to gcode --step-size 0.025 >mm.gcode || fail "--step-size: exit $?"
grep -q '^G1 X1 Y0.425$' mm.gcode || fail "--step-size output"
# auto picks a profile; svg output is a picture with the segments
"$BIN" segment plot8.fc --to json >plot8.json || fail "auto: exit $?"
grep -q '"profile":"eval8"' plot8.json || fail "auto on eval8 data"
"$BIN" segment plot8.fc --to svg --overlay -o plot.svg || fail "svg: exit $?"
head -c 200 plot.svg | grep -q '<svg' || fail "svg: not an svg"
grep -q '<polyline' plot.svg || fail "svg: no chain polyline"
grep -q '<line ' plot.svg || fail "svg: no segments"
# plain SVG (the default): one path per chain, the steps as user units
"$BIN" segment lines.fc --profile eval8 --to svg -o lines.svg || fail "plain svg: exit $?"
grep -q '<path d="M0 0 L40 17 L-3 5"/>' lines.svg || fail "plain svg: path $(cat lines.svg)"
grep -q 'transform="scale(1,-1)"' lines.svg || fail "plain svg: y not flipped"
grep -q '<!-- profile eval8: ' lines.svg || fail "plain svg: no profile comment"
expect_err "--overlay without svg" 2 "--overlay needs --to svg" \
    "$BIN" segment lines.fc --to gcode --overlay
# points input, format given
printf '0 0\n1 0\n2 1\n' | "$BIN" segment --format points --profile eval8 --to gcode -c >points.gcode \
    || fail "points input: exit $?"
grep -q '^G1 X2 Y1$' points.gcode || fail "points input"

# Steps -> vectors -> steps is exact: vectors carry no phase, so segment
# writes only default-phase segments, proved by redrawing them before
# writing. The example of G1 X7 Y3 / X20 Y5 / X30 Y30 under every profile
# comes back as its own three vertices.
printf 'G0 X0 Y0\nG1 X7 Y3\nX20 Y5\nX30 Y30\n' >three.gcode
for p in eval4 eval8 patent grbl marlin; do
    "$BIN" interpolate --profile "$p" three.gcode -o "three-$p.fc"
    got=$("$BIN" segment "three-$p.fc" --profile "$p" --to gcode | grep '^G1' | tr '\n' ' ')
    [ "$got" = "G1 X7 Y3 G1 X20 Y5 G1 X30 Y30 " ] || fail "three $p: '$got'"
done
# round_trip NAME CHAINS PROFILE: --to gcode and hpgl under PROFILE (auto:
# the profile named in the output's comment) redraw into CHAINS.
round_trip() {
    local name=$1 chains=$2 profile=$3 to redraw
    for to in gcode hpgl; do
        "$BIN" segment "$chains" --profile "$profile" --to "$to" -o "$name.$to" -v 2>"$name.err" \
            || { fail "$name $to: exit $? $(cat "$name.err")"; continue; }
        redraw=$(sed -n 's/.*profile \([a-z0-9]*\): `stepzip interpolate --profile \1`.*/\1/p' \
            "$name.$to" | head -1)
        [ -n "$redraw" ] || { fail "$name $to: no profile comment"; continue; }
        [ "$profile" = auto ] || [ "$redraw" = "$profile" ] || fail "$name $to: comment names $redraw"
        grep -q "^stepzip: profile $redraw" "$name.err" || fail "$name $to: -v: $(cat "$name.err")"
        "$BIN" interpolate --profile "$redraw" "$name.$to" -o "$name.$to.fc"
        "$BIN" segment "$chains" --profile "$redraw" --to json -q >"$name.json" \
            || fail "$name: json: exit $?"
        grep -q '"steps":' "$name.json" || fail "$name: json"
        cmp -s "$chains" "$name.$to.fc" || fail "$name $to: redrawn chains differ (profile $redraw)"
    done
}
# polylines drawn by each profile: the Hershey specimen sheet of corpora/plotter
for p in eval4 eval8 patent grbl marlin; do
    round_trip "hershey-$p" "$SRC/corpora/plotter/hershey-$p.fc" "$p"
done
round_trip hershey-auto "$SRC/corpora/plotter/hershey-grbl.fc" auto
round_trip gnuplot-eval4 "$SRC/corpora/plotter/gnuplot-eval4.fc" eval4
# Bresenham-stepped plots (textbook error term 2dy - dx: no profile's own
# phase), 8-connected and as a 4-connected staircase, under every profile
# that takes them
bresenham() {  # bresenham FOUR: a star of lines from (0, 0) as one chain
    awk -v four="$1" 'function abs(v) { return v < 0 ? -v : v }
    function line(dx, dy,   ax, ay, sx, sy, xm, maj, mnr, e, i, d) {
        ax = abs(dx); ay = abs(dy); sx = dx < 0 ? -1 : 1; sy = dy < 0 ? -1 : 1
        xm = ax >= ay; maj = xm ? ax : ay; mnr = xm ? ay : ax; e = 2 * mnr - maj
        for (i = 0; i < maj; i++) {
            if (e > 0) {
                e -= 2 * maj
                if (four) out = out code(xm ? sx : 0, xm ? 0 : sy) code(xm ? 0 : sx, xm ? sy : 0)
                else out = out code(sx, sy)
            } else out = out code(xm ? sx : 0, xm ? 0 : sy)
            e += 2 * mnr
        }
    }
    function code(x, y) { return x == 1 ? (y == 1 ? 1 : y == -1 ? 7 : 0) : x == -1 ? (y == 1 ? 3 : y == -1 ? 5 : 4) : (y == 1 ? 2 : 6) }
    BEGIN { out = ""; n = split("97 41 -13 88 -120 -7 5 -66 70 -23 -1 55 -59 -91 131 12", v, " ")
        for (k = 1; k < n; k += 2) line(v[k], v[k + 1])
        print "0 0 " out }'
}
bresenham 0 >bres8.fc
bresenham 1 >bres4.fc
for p in eval8 grbl marlin auto; do round_trip "bres8-$p" bres8.fc "$p"; done
for p in eval4 patent eval8 grbl marlin auto; do round_trip "bres4-$p" bres4.fc "$p"; done
# pens: HP-GL's SP survives as "# pen N" comments of the chain file and
# comes back as SP (HP-GL) or T (G-code)
printf 'SP2;PU0,0;PD10,0;SP3;PD10,10;PU20,20;PD25,25;SP1;PD30,25;' >pens.plt
for fmt in freeman points; do
    "$BIN" interpolate --profile eval8 pens.plt --to "$fmt" -o "pens.$fmt"
    [ "$(grep -c '^# pen ' "pens.$fmt")" -eq 3 ] || fail "pens $fmt: $(cat "pens.$fmt")"
    got=$("$BIN" segment "pens.$fmt" --profile eval8 --to hpgl | grep -o 'SP[0-9]*' | tr '\n' ' ')
    [ "$got" = "SP2 SP3 SP1 SP0 " ] || fail "pens $fmt hpgl: '$got'"
    got=$("$BIN" segment "pens.$fmt" --profile eval8 --to gcode | grep '^T' | tr '\n' ' ')
    [ "$got" = "T2 T3 T1 " ] || fail "pens $fmt gcode: '$got'"
    "$BIN" segment "pens.$fmt" --profile eval8 --to hpgl | "$BIN" interpolate --profile eval8 \
        --to "$fmt" -o "pens2.$fmt"
    cmp -s "pens.$fmt" "pens2.$fmt" || fail "pens $fmt: round trip differs"
done

# the patent segmenter's read-out is a study mode: it says when its vectors
# do not redraw the input
"$BIN" segment fig5.fc --segmenter patent --to gcode -o fig5b.gcode 2>note.txt
grep -q 'the vectors do not redraw the input exactly' note.txt || fail "fig5 redraw note: $(cat note.txt)"
grep -q 'do not redraw the input steps exactly' fig5b.gcode || fail "fig5 comment: $(cat fig5b.gcode)"

# errors: one line, exit 1, no output file
expect_err "no overwrite" 1 "plot.svg: already exists" "$BIN" segment plot8.fc --to svg -o plot.svg
printf '0 0 0029\n' >bad.fc
expect_err "bad chain" 1 "bad.fc:1:8: " "$BIN" segment bad.fc --format freeman --to gcode -o bad.gcode
[ ! -e bad.gcode ] || fail "partial output after an error"
echo '0 0 0101' >diag.fc
expect_err "4-connected profile on diagonal steps" 1 "diag.fc: chain 1: " \
    "$BIN" segment diag.fc --profile eval4 --to gcode -o diag.gcode
[ ! -e diag.gcode ] || fail "partial output after a connectivity error"
expect_err "patent on diagonals" 1 "diag.fc: chain 1: " \
    "$BIN" segment diag.fc --segmenter patent --to gcode
printf 'hello\n' >hello.txt
expect_err "undetected" 1 "hello.txt: not a chain file" "$BIN" segment hello.txt --to gcode
expect_err "missing input" 1 "nothere.fc: " "$BIN" segment nothere.fc --to gcode
left=$(find . -maxdepth 1 -name '*.stepzip-*' -print)
[ -z "$left" ] || fail "temporary file left behind: $left"
# usage errors: exit 2
expect_err "no --to" 2 "--to is required" "$BIN" segment fig5.fc
expect_err "bad --to" 2 "unknown output 'png'" "$BIN" segment fig5.fc --to png
expect_err "bad segmenter" 2 "unknown segmenter" "$BIN" segment fig5.fc --to gcode --segmenter fast
expect_err "bad profile" 2 "unknown profile" "$BIN" segment fig5.fc --to gcode --profile x

# --arc-method: a job of lines and arcs, stepped by each arc method, comes back
# with its three arcs as G2/G3, and the written G-code redraws the same steps.
printf '%s\n' 'G0 X0 Y0' 'G1 X60 Y10' 'G3 X100 Y50 I0 J40' 'G1 X90 Y120' \
    'G2 X150 Y180 I60 J0' 'G1 X150 Y80' 'G2 X110 Y40 I-40 J0' >arcs.gcode
for method in evaluation accelerated dda prediction recursion; do
    case $method in evaluation | prediction) prof=eval4 ;; *) prof=eval8 ;; esac
    "$BIN" interpolate --profile $prof --arc-method $method arcs.gcode --to freeman \
        -o "arcs-$method.fc" || fail "arcs $method: interpolate exit $?"
    "$BIN" segment "arcs-$method.fc" --profile $prof --arc-method $method --to gcode \
        -o "arcs-$method.out.gcode" || fail "arcs $method: segment exit $?"
    n=$(grep -c '^G[23] X-*[0-9]* Y-*[0-9]* I-*[0-9]* J-*[0-9]*$' "arcs-$method.out.gcode" || true)
    [ "$n" -eq 3 ] || fail "arcs $method: $n G2/G3 X Y I J moves, expected 3"
    "$BIN" interpolate --profile $prof --arc-method $method "arcs-$method.out.gcode" \
        --to freeman -o "arcs-$method.again.fc" || fail "arcs $method: redraw exit $?"
    cmp -s "arcs-$method.fc" "arcs-$method.again.fc" ||
        fail "arcs $method: the written G-code redraws other steps"
done
expect_err "arc method unknown" 2 "unknown arc method 'spiral'" \
    "$BIN" segment arcs-dda.fc --to gcode --arc-method spiral
expect_err "arc method not gcode" 2 "--arc-method needs --to gcode" \
    "$BIN" segment arcs-dda.fc --to svg --arc-method dda
expect_err "min-arc alone" 2 "--min-arc needs --arc-method" \
    "$BIN" segment arcs-dda.fc --to gcode --min-arc 5

if [ "$failures" -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "segment: all passed"
