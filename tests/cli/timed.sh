#!/usr/bin/env bash
# --format timed: a STEP/DIR log with idle ticks read with time as axis 0.
# Round trip of corpora/timed/ at level 3, and of the 2-axis stream at 19
# (compress, verify, decompress, byte-compare); the frame names the format;
# the timed reading is smaller than the steps reading on the 2-axis stream.
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
  "$stepzip" info "$work/t.stz" | grep -q '^input format: *timed$' || { echo "FAIL info format: $f"; fail=1; }
done
f=$src/corpora/timed/trapezoid-2axis.steps
"$stepzip" compress -q -f --format timed "$f" -o "$work/t.stz"
"$stepzip" compress -q -f --format steps "$f" -o "$work/s.stz"
t=$(wc -c < "$work/t.stz"); s=$(wc -c < "$work/s.stz")
[ "$t" -lt "$s" ] || { echo "FAIL timed $t bytes not below steps $s bytes: $f"; fail=1; }
# An unknown format name is a usage error naming it.
if "$stepzip" compress -q -f --format timing "$f" -o "$work/u.stz" 2>"$work/err"; then
  echo "FAIL --format timing accepted"; fail=1
fi
grep -q "timing" "$work/err" || { echo "FAIL error does not name the format"; fail=1; }
[ ! -e "$work/u.stz" ] || { echo "FAIL output written on a usage error"; fail=1; }
[ $fail = 0 ] && echo "timed: ok"
exit $fail
