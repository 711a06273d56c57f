#!/usr/bin/env bash
# Round trip of every file in corpora/ under every profile that fits it:
# compress, verify, decompress, compare byte for byte. The named profiles
# run at levels 1 and 3 (the default); --profile auto at 3 and 19 (the
# highest). eval8, grbl and marlin take any chain of up to six axes and must
# fit every file; eval4 and patent take two-axis 4-connected chains only and
# may refuse a file only with the profile-does-not-fit error, which is
# reported as a skip. (Every level on every profile is the matrix of
# tests/roundtrip_matrix_test.cpp.)
# Usage: bash corpora.sh <stepzip-binary> <source-dir>
set -euo pipefail
stepzip=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
n=0
skips=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# round_trip FILE LEVEL PROFILE: one compress/verify/decompress/compare;
# returns 1 when the profile does not fit the file (a skip, reported).
round_trip() {
  local f=$1 level=$2 profile=$3 rc=0
  "$stepzip" compress -q -f -L "$level" --profile "$profile" "$f" -o "$work/x.stz" 2>"$work/err.log" || rc=$?
  if [ $rc -ne 0 ]; then
    case $profile in
      eval4 | patent)
        if [ $rc -eq 1 ] && grep -Eq "profile $profile (cannot represent it|does not take)" "$work/err.log"; then
          echo "skip: profile $profile does not fit $f: $(cat "$work/err.log")"
          skips=$((skips + 1))
          return 1
        fi ;;
    esac
    fail "compress -L $level --profile $profile $f (exit $rc): $(cat "$work/err.log")"
    return 0
  fi
  n=$((n + 1))
  rc=0
  "$stepzip" verify "$work/x.stz" "$f" >/dev/null 2>"$work/err.log" || rc=$?
  [ $rc -eq 0 ] || { fail "verify -L $level --profile $profile $f (exit $rc): $(cat "$work/err.log")"; return 0; }
  rc=0
  "$stepzip" decompress -q -f "$work/x.stz" -o "$work/x.out" 2>"$work/err.log" || rc=$?
  [ $rc -eq 0 ] || { fail "decompress -L $level --profile $profile $f (exit $rc): $(cat "$work/err.log")"; return 0; }
  cmp -s "$work/x.out" "$f" || fail "decompressed bytes differ: -L $level --profile $profile $f"
  rm -f "$work/x.stz" "$work/x.out"
}

files=0
for f in "$src"/corpora/*/*.fc "$src"/corpora/*/*.steps "$src"/corpora/*/*.hpgl "$src"/corpora/samples/*; do
  [ -f "$f" ] || continue
  files=$((files + 1))
  case "$f" in
    *.hpgl | *.gcode)
      # vectors: step them first, then the chain file is the input
      input=$work/$(basename "$f").fc
      "$stepzip" interpolate --profile grbl "$f" -o "$input" -f ;;
    *) input=$f ;;
  esac
  for profile in eval4 eval8 patent grbl marlin; do
    for level in 1 3; do round_trip "$input" $level $profile || break; done
  done
  for level in 3 19; do round_trip "$input" $level auto || fail "auto refused $input"; done
done
echo "corpora: $files files, $n round trips, $skips skipped (profile does not fit), $fails failure(s)"
[ $files -gt 0 ] || { echo "FAIL: no corpus file found"; exit 1; }
[ $fails -eq 0 ]
