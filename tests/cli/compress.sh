#!/usr/bin/env bash
# CLI tests of compress / decompress / verify / info (SPEC section 6).
# Usage: bash compress.sh <stepzip-binary> <source-dir>
set -u
Z=$(realpath "$1")
SRC=$(realpath "$2")
W=$(mktemp -d)
trap 'chmod -R u+w "$W"; rm -rf "$W"' EXIT
cd "$W"
fails=0
check() { # check "what" command... : expects success
    local what=$1; shift
    if ! "$@" >out.log 2>err.log; then echo "FAIL: $what"; cat err.log; fails=$((fails + 1)); fi
}
refuse() { # refuse "what" command... : expects exit 1 and one line on stderr
    local what=$1; shift
    "$@" >out.log 2>err.log
    local rc=$?
    if [ $rc -ne 1 ]; then echo "FAIL: $what (exit $rc, expected 1)"; fails=$((fails + 1)); fi
    if [ "$(wc -l <err.log)" -ne 1 ]; then echo "FAIL: $what (stderr is not one line)"; cat err.log; fails=$((fails + 1)); fi
}

cp "$SRC/tests/golden/plotter.fc" a.fc
cp "$SRC/tests/golden/four.fc" b.fc

# FILE -> FILE.stz, keep input by default, decompress strips .stz
check "compress file" "$Z" compress a.fc
[ -f a.fc.stz ] && [ -f a.fc ] || { echo "FAIL: a.fc.stz missing or input removed"; fails=$((fails + 1)); }
mv a.fc a.orig
check "decompress file" "$Z" decompress a.fc.stz
cmp -s a.fc a.orig || { echo "FAIL: decompressed file differs"; fails=$((fails + 1)); }

# existing output without -f is refused and left untouched; -f overwrites
cp a.fc.stz keep.stz
refuse "overwrite without -f" "$Z" compress a.fc
cmp -s a.fc.stz keep.stz || { echo "FAIL: existing output was touched"; fails=$((fails + 1)); }
grep -q 'already exists' err.log || { echo "FAIL: no 'already exists' message"; fails=$((fails + 1)); }
check "overwrite with -f" "$Z" compress -f a.fc

# stdin -> stdout, -c, -o, aliases
"$Z" compress -f <a.fc >s.stz && "$Z" decompress <s.stz >s.out && cmp -s s.out a.fc \
    || { echo "FAIL: stdin/stdout round trip"; fails=$((fails + 1)); }
"$Z" compress -f - <b.fc | "$Z" -d - >b.out && cmp -s b.out b.fc \
    || { echo "FAIL: '-' round trip through a pipe"; fails=$((fails + 1)); }
"$Z" compress -c b.fc >c.stz && "$Z" decompress -c c.stz | cmp -s - b.fc \
    || { echo "FAIL: -c round trip"; fails=$((fails + 1)); }
check "-o" "$Z" -z b.fc -o named.bin --profile patent --segmenter patent -L 19 -T 2
check "decompress -o" "$Z" decompress named.bin -o named.out
cmp -s named.out b.fc || { echo "FAIL: -o round trip"; fails=$((fails + 1)); }
refuse "decompress of a name without .stz" "$Z" decompress named.bin

# -T 1 and -T 2 give the same bytes
"$Z" compress -c --block-size 50 -T 1 a.fc >t1.stz
"$Z" compress -c --block-size 50 -T 2 a.fc >t2.stz
cmp -s t1.stz t2.stz || { echo "FAIL: -T 1 and -T 2 differ"; fails=$((fails + 1)); }

# --rm removes the input only after success
cp b.fc r.fc
check "--rm" "$Z" compress --rm r.fc
[ ! -e r.fc ] && [ -f r.fc.stz ] || { echo "FAIL: --rm"; fails=$((fails + 1)); }

# verify and info
check "verify" "$Z" verify a.fc.stz
check "verify against the original" "$Z" verify a.fc.stz a.fc
refuse "verify against another file" "$Z" verify a.fc.stz b.fc
grep -q 'differ' err.log || { echo "FAIL: verify mismatch message"; fails=$((fails + 1)); }
check "info" "$Z" info named.bin
for k in profile: chains: steps: segments: bits/step: 'compressed size:' patent:; do
    grep -q "$k" out.log || { echo "FAIL: info lacks $k"; fails=$((fails + 1)); }
done
grep -q 'profile: *patent' out.log || { echo "FAIL: info profile"; fails=$((fails + 1)); }

# errors: one line, exit 1, nothing left behind
refuse "unreadable input" "$Z" compress missing.fc
printf '0 0 01x2\n' >bad.fc
refuse "syntax error" "$Z" compress --format freeman bad.fc
grep -q 'bad.fc:1:' err.log || { echo "FAIL: syntax error does not name line:column"; cat err.log; fails=$((fails + 1)); }
[ ! -e bad.fc.stz ] || { echo "FAIL: output left after an error"; fails=$((fails + 1)); }
refuse "corrupt input" "$Z" decompress "$SRC/tests/golden-errors/block_checksum.stz" -o x.out
[ ! -e x.out ] || { echo "FAIL: partial output after a corrupt input"; fails=$((fails + 1)); }
grep -q 'byte ' err.log || { echo "FAIL: corrupt message lacks a byte offset"; fails=$((fails + 1)); }
refuse "verify of a corrupt file" "$Z" verify "$SRC/tests/golden-errors/content_checksum.stz"
if [ -e /dev/full ]; then
    "$Z" compress -c a.fc >/dev/full 2>err.log
    [ $? -eq 1 ] || { echo "FAIL: /dev/full exit status"; fails=$((fails + 1)); }
fi
ls -a | grep -q stepzip- && { echo "FAIL: temporary file left behind"; fails=$((fails + 1)); }

# usage errors exit 2
"$Z" compress --profile nope a.fc 2>/dev/null
[ $? -eq 2 ] || { echo "FAIL: unknown profile is not a usage error"; fails=$((fails + 1)); }

if [ $fails -ne 0 ]; then echo "$fails failure(s)"; exit 1; fi
echo "compress.sh: all passed"
