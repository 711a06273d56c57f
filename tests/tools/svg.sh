#!/usr/bin/env bash
# SVG with a real renderer as judge: rsvg-convert renders what
# `stepzip segment --to svg` writes, and the PNG shows the chains where they
# are (tests/tools/svg_check.py decodes it with the standard library).
# Usage: bash svg.sh <stepzip-binary> <source-dir> [python3]
# Exit 77 (skipped) when rsvg-convert is not installed. Every command's exit
# status is checked: a failed command is a failure, never a skipped check.
set -euo pipefail
BIN=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
PY=${3:-python3}
if ! command -v rsvg-convert >/dev/null; then
    echo "SKIP: rsvg-convert is not installed (Debian package librsvg2-bin; scripts/setup-deps installs it)"
    exit 77
fi
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# check NAME CHAINS.fc [segment options...]
check() {
    local name=$1 chains=$2
    shift 2
    "$BIN" segment "$chains" --to svg --overlay -q "$@" >"$name.svg" 2>"$name.err" \
        || { fail "$name: segment: $(cat "$name.err")"; return; }
    rsvg-convert -o "$name.png" "$name.svg" 2>"$name.err" \
        || { fail "$name: rsvg-convert: $(cat "$name.err")"; return; }
    [ ! -s "$name.err" ] || fail "$name: rsvg-convert said: $(cat "$name.err")"
    $PY "$SRC/tests/tools/svg_check.py" "$name.svg" "$name.png" "$chains" >"$name.out" 2>&1 \
        || fail "$name: $(cat "$name.out")"
    echo "$name: $(cat "$name.out")"
}

printf '0 0 00000000002222222222\n' >ell.fc
check ell ell.fc --profile eval8
check ell-auto ell.fc
printf '0 0 0001000100010001\n20 5 66665555444433\n3 12 7\n' >three.fc
check three three.fc
check three-optimal three.fc --segmenter optimal --profile grbl
printf '0 0 02002002000\n' >fig5.fc
check fig5-patent fig5.fc --segmenter patent
if "$BIN" interpolate --profile eval8 "$SRC/corpora/samples/plot.gcode" >plot.fc 2>plot.err; then
    check plot plot.fc
else
    fail "plot: interpolate: $(cat plot.err)"
fi

if [ "$failures" -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "svg: all checks passed"
