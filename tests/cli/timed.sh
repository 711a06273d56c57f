#!/usr/bin/env bash
# --format timed: a STEP/DIR log with idle ticks read with time as axis 0.
# Round trip of corpora/timed/ at level 3, and of the 2-axis stream at 19
# (compress, verify, decompress, byte-compare); the frame names the format.
# (The steps reading's gap lists, docs/formats.md, now make it smaller than
# the timed reading at level 3 on the 2-axis stream: 6324 against 6916 bytes.)
set -euo pipefail
stepzip=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
for f in "$src"/corpora/timed/*.steps; do
  levels=3
  case "$f" in *2axis*) levels="3 19" ;; esac
  for level in $levels; do
    "$stepzip" compress -q -f --format timed -L $level "$f" -o "$work/t.stz"
    "$stepzip" verify "$work/t.stz" "$f" >/dev/null || { echo "FAIL verify -L $level: $f"; fail=1; }
    "$stepzip" decompress -q -f "$work/t.stz" -o "$work/t.out"
    cmp -s "$work/t.out" "$f" || { echo "FAIL decompress differs -L $level: $f"; fail=1; }
  done
  info=$("$stepzip" info "$work/t.stz")
  grep -q '^input format: *timed$' <<< "$info" || { echo "FAIL info format: $f"; fail=1; }
done
f=$src/corpora/timed/trapezoid-2axis.steps
# An unknown format name is a usage error naming it.
if "$stepzip" compress -q -f --format timing "$f" -o "$work/u.stz" 2>"$work/err"; then
  echo "FAIL --format timing accepted"; fail=1
fi
grep -q "timing" "$work/err" || { echo "FAIL error does not name the format"; fail=1; }
[ ! -e "$work/u.stz" ] || { echo "FAIL output written on a usage error"; fail=1; }
# segment: the moves of the 2-axis stream (planned at 500 mm/s^2, 80 steps/mm:
# 40000 steps/s^2 and at most 8000 steps/s on the leading axis; its first
# move is 2567,4337 steps from rest to rest at the rate limit).
"$stepzip" segment --format timed --tick-us 30 --to json "$f" -o "$work/m.json" -f
first=$(grep -m1 '"delta":\[2567,4337\]' "$work/m.json" || true)
[ -n "$first" ] || { echo "FAIL segment json: first move not found"; fail=1; }
lead_of() { sed -n "s/.*\"$1\":\([0-9.]*\).*/\1/p" <<<"$first" | awk '{printf "%.0f", $1 * 4337 / 5039.75}'; }
cruise=$(lead_of cruise); acc=$(lead_of acceleration); entry=$(lead_of entry)
[ "${cruise:-0}" -ge 7760 ] && [ "${cruise:-0}" -le 8240 ] || { echo "FAIL cruise $cruise not 8000 +-3%"; fail=1; }
[ "${acc:-0}" -ge 38000 ] && [ "${acc:-0}" -le 42000 ] || { echo "FAIL acceleration $acc not 40000 +-5%"; fail=1; }
[ "${entry:-1}" -le 240 ] || { echo "FAIL entry $entry not from rest"; fail=1; }
# Per axis (the "axes" of the chain): the rate limit and the acceleration,
# 8000 steps/s within 2 % and 40000 steps/s^2 within 10 %, on both axes.
axes=$(python3 -c 'import json, sys; print(" ".join("%.0f,%.0f" % (a["max_rate"], a["acceleration"]) for a in json.load(open(sys.argv[1]))["chains"][0]["axes"]))' "$work/m.json")
[ "$(wc -w <<<"$axes")" -eq 2 ] || { echo "FAIL segment json: axes '$axes'"; fail=1; }
for a in $axes; do
  rate=${a%,*} acc=${a#*,}
  [ "$rate" -ge 7840 ] && [ "$rate" -le 8160 ] && [ "$acc" -ge 36000 ] && [ "$acc" -le 44000 ] ||
    { echo "FAIL segment json: axis rate $rate, acceleration $acc"; fail=1; }
done
"$stepzip" segment --format timed --tick-us 30 --to gcode --feed timed --step-size 0.0125 "$f" -o "$work/m.nc" -f
# F of the first move: 8000 steps/s on y, 9296 along the path, 6972 mm/min at 0.0125 mm/step.
feed=$(sed -n 's/^G1 X32.0875 Y54.2125 F\([0-9]*\).*/\1/p' "$work/m.nc" | head -n 1)
[ "${feed:-0}" -ge 6763 ] && [ "${feed:-0}" -le 7181 ] || { echo "FAIL gcode: first move's F $feed not 6972 +-3%"; fail=1; }
if "$stepzip" segment --format timed --to json "$f" -o "$work/n.json" 2>"$work/err"; then
  echo "FAIL --format timed without --tick-us accepted"; fail=1
fi
grep -q -- "--tick-us" "$work/err" || { echo "FAIL error does not name --tick-us"; fail=1; }
[ ! -e "$work/n.json" ] || { echo "FAIL output written on a usage error"; fail=1; }
# The thorough levels code a block both as a tick block and as an interrupt
# block and keep the smaller; the default level takes the one its check
# chose. On a log made here whose two axes step at their own times (a
# period ramped every 250 ticks, one axis at a quarter of it, the other at
# 0.7 of it, as no single interrupt steps them) the default writes the
# interrupt block, the tick block is smaller: -L 19 keeps it (598 against
# 616 bytes when this was written).
python3 - "$work/b.steps" <<'PY'
import sys
period, nx, ny, out = 40.0, 3.3, 7.9, bytearray()
for t in range(60000):
    if t % 250 == 0:
        period += -0.35 if t < 20000 else 0.0 if t < 40000 else 0.35
    b = 8
    if t >= nx:
        b |= 1
        nx += period / 4
    if t >= ny:
        b |= 4
        ny += period * 0.7
    out.append(b)
open(sys.argv[1], 'wb').write(bytes(out))
PY
for level in 3 19; do
  "$stepzip" compress -q -f --format timed -L $level "$work/b.steps" -o "$work/b$level.stz"
  "$stepzip" decompress -q -f "$work/b$level.stz" -o "$work/b.out"
  cmp -s "$work/b.out" "$work/b.steps" || { echo "FAIL decompress differs -L $level: b.steps"; fail=1; }
done
s3=$(wc -c < "$work/b3.stz"); s19=$(wc -c < "$work/b19.stz")
[ "$s19" -lt "$s3" ] || { echo "FAIL -L 19 ($s19 bytes) not smaller than -L 3 ($s3)"; fail=1; }
[ $fail = 0 ] && echo "timed: ok"
exit $fail
