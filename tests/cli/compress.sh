#!/usr/bin/env bash
# CLI tests of compress / decompress / verify / info (SPEC section 6).
# Every command's exit status is checked: `check` expects 0, `expect_exit N`
# expects exactly N (and one stderr line when N is 1 or 2).
# Usage: bash compress.sh <stepzip-binary> <source-dir>
set -euo pipefail
Z=$(realpath "$1")
SRC=$(realpath "$2")
W=$(mktemp -d)
trap 'chmod -R u+w "$W"; rm -rf "$W"' EXIT
cd "$W"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
check() { # check "what" command... : expects exit 0
    local what=$1 rc=0; shift
    "$@" >out.log 2>err.log || rc=$?
    if [ $rc -ne 0 ]; then fail "$what (exit $rc)"; cat err.log; fi
    return 0
}
expect_exit() { # expect_exit N "what" command... : expects exit N, one line on stderr
    local want=$1 what=$2 rc=0; shift 2
    "$@" >out.log 2>err.log || rc=$?
    [ $rc -eq "$want" ] || fail "$what (exit $rc, expected $want)"
    [ "$(wc -l <err.log)" -eq 1 ] || { fail "$what (stderr is not one line)"; cat err.log; }
    return 0
}
refuse() { expect_exit 1 "$@"; }
same() { # same "what" FILE1 FILE2
    cmp -s "$2" "$3" || fail "$1: $2 and $3 differ"
}

cp "$SRC/tests/golden/plotter.fc" a.fc
cp "$SRC/tests/golden/four.fc" b.fc
[ -s a.fc ] && [ -s b.fc ] || fail "setup: empty inputs"

# FILE -> FILE.stz, keep input by default, decompress strips .stz
check "compress file" "$Z" compress a.fc
[ -f a.fc.stz ] && [ -f a.fc ] || fail "a.fc.stz missing or input removed"
mv a.fc a.orig
check "decompress file" "$Z" decompress a.fc.stz
same "decompressed file" a.fc a.orig

# existing output without -f is refused and left untouched; -f overwrites
cp a.fc.stz keep.stz
refuse "overwrite without -f" "$Z" compress a.fc
same "existing output untouched" a.fc.stz keep.stz
grep -q 'already exists' err.log || fail "no 'already exists' message"
check "overwrite with -f" "$Z" compress -f a.fc

# stdin -> stdout, -c, -o, aliases: each step checked on its own
check "compress stdin -> stdout" sh -c '"$1" compress -f <a.fc >s.stz' sh "$Z"
check "decompress stdin -> stdout" sh -c '"$1" decompress <s.stz >s.out' sh "$Z"
same "stdin/stdout round trip" s.out a.fc
check "'-' through a pipe" bash -c 'set -o pipefail; "$1" compress -f - <b.fc | "$1" -d - >b.out' sh "$Z"
same "'-' round trip" b.out b.fc
check "compress -c" sh -c '"$1" compress -c b.fc >c.stz' sh "$Z"
check "decompress -c" sh -c '"$1" decompress -c c.stz >c.out' sh "$Z"
same "-c round trip" c.out b.fc
check "-o" "$Z" -z b.fc -o named.bin --profile patent --segmenter patent -L 19 -T 2
check "decompress -o" "$Z" decompress named.bin -o named.out
same "-o round trip" named.out b.fc
refuse "decompress of a name without .stz" "$Z" decompress named.bin

# -T 1 and -T 2 give the same bytes, and those bytes decode to the input
# (two failed runs would leave two equal empty files)
for t in 1 2; do
    check "compress -T $t" sh -c '"$1" compress -c --block-size 50 -T "$2" a.fc >t$2.stz' sh "$Z" $t
    [ -s t$t.stz ] || fail "-T $t wrote nothing"
    check "decompress the -T $t output" "$Z" decompress -c t$t.stz
    same "-T $t round trip" out.log a.fc
done
same "-T 1 and -T 2 output" t1.stz t2.stz

# --rm removes the input only after success
cp b.fc r.fc
check "--rm" "$Z" compress --rm r.fc
[ ! -e r.fc ] && [ -f r.fc.stz ] || fail "--rm"

# verify and info
check "verify" "$Z" verify a.fc.stz
check "verify against the original" "$Z" verify a.fc.stz a.fc
refuse "verify against another file" "$Z" verify a.fc.stz b.fc
grep -q 'differ' err.log || fail "verify mismatch message"
check "info" "$Z" info named.bin
for k in profile: chains: steps: segments: bits/step: 'compressed size:' patent:; do
    grep -q "$k" out.log || fail "info lacks $k"
done
grep -q 'profile: *patent' out.log || fail "info profile"

# errors: one line, exit 1, nothing left behind
refuse "unreadable input" "$Z" compress missing.fc
printf '0 0 01x2\n' >bad.fc
refuse "syntax error" "$Z" compress --format freeman bad.fc
grep -q 'bad.fc:1:' err.log || { fail "syntax error does not name line:column"; cat err.log; }
[ ! -e bad.fc.stz ] || fail "output left after an error"
refuse "corrupt input" "$Z" decompress "$SRC/tests/golden-errors/block_checksum.stz" -o x.out
[ ! -e x.out ] || fail "partial output after a corrupt input"
grep -q 'byte ' err.log || fail "corrupt message lacks a byte offset"
refuse "verify of a corrupt file" "$Z" verify "$SRC/tests/golden-errors/content_checksum.stz"
if [ -e /dev/full ]; then
    refuse "compress -c to a full disk" sh -c '"$1" compress -c a.fc >/dev/full' sh "$Z"
else
    echo "skip: /dev/full is missing, the full-disk check did not run"
fi
left=$(find . -maxdepth 1 -name '*stepzip-*' -print)
[ -z "$left" ] || fail "temporary file left behind: $left"

# usage errors exit 2
expect_exit 2 "unknown profile is a usage error" "$Z" compress --profile nope a.fc

if [ $fails -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
fi
echo "compress.sh: all passed"
