#!/usr/bin/env bash
# Round trip of every file in corpora/ (all profiles that fit, the default and
# the highest level): compress, verify, decompress, compare byte for byte.
set -euo pipefail
stepzip=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
n=0
for f in "$src"/corpora/*/*.fc "$src"/corpora/*/*.steps "$src"/corpora/*/*.hpgl "$src"/corpora/samples/*; do
  [ -f "$f" ] || continue
  case "$f" in
    *.hpgl|*.gcode)
      # vectors: step them first, then the chain file is the input
      "$stepzip" interpolate --profile grbl "$f" -o "$work/in.fc" -f
      input=$work/in.fc ;;
    *) input=$f ;;
  esac
  for level in 3 19; do
    n=$((n + 1))
    if ! "$stepzip" compress -q -f -L $level "$input" -o "$work/x.stz"; then
      echo "FAIL compress -L $level: $f"; fail=1; continue
    fi
    if ! "$stepzip" verify "$work/x.stz" "$input" >/dev/null; then
      echo "FAIL verify -L $level: $f"; fail=1; continue
    fi
    "$stepzip" decompress -q -f "$work/x.stz" -o "$work/x.out"
    if ! cmp -s "$work/x.out" "$input"; then
      echo "FAIL decompress differs -L $level: $f"; fail=1
    fi
  done
done
echo "corpora round trips: $n"
[ $n -gt 0 ] || { echo "FAIL no corpus file found"; exit 1; }
exit $fail
