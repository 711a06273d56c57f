#!/usr/bin/env bash
# The command-line habits stepzip shares with zstd (docs/cli.md, "zstd ->
# stepzip"): each check runs the same command line with zstd, where zstd is
# the reference, and with stepzip, and compares exit codes and effects.
# Usage: habits.sh STEPZIP SOURCE_DIR
set -euo pipefail

Z=$(realpath "$1")
SRC=$(realpath "$2")
command -v zstd >/dev/null || { echo "zstd is not installed (scripts/setup-deps installs it)"; exit 1; }

W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
cd "$W"

passed=0
skipped=0
fail() { echo "FAIL: $*"; exit 1; }
pass() { passed=$((passed + 1)); echo "ok: $1"; }
skip() { skipped=$((skipped + 1)); echo "skip: $1"; }

# run CMD...: runs CMD with stdout in out.log and stderr in err.log; sets rc.
run() {
  set +e
  "$@" >out.log 2>err.log
  rc=$?
  set -e
}
# want_rc WANT NAME CMD...: CMD must exit with WANT.
want_rc() {
  local want=$1 name=$2
  shift 2
  run "$@"
  [ "$rc" -eq "$want" ] || { cat err.log; fail "$name: exit $rc, expected $want"; }
}
# same_rc NAME 'ZSTD ARGS' 'STEPZIP ARGS': both exit alike; sets zrc and src.
same_rc() {
  local name=$1
  run bash -c "zstd $2"; zrc=$rc
  run bash -c "\"$Z\" $3"; src=$rc
  [ "$zrc" -eq "$src" ] || { cat err.log; fail "$name: stepzip exit $src, zstd exit $zrc"; }
}

fresh() {  # fresh inputs: a.fc (a plotter chain file), b.fc (one short chain)
  rm -rf ./*
  cp "$SRC/corpora/plotter/hershey-grbl.fc" a.fc
  printf '0 0 0011223344556677\n' > b.fc
}

# ---------------------------------------------------------------- data risks

# -c with two inputs writes both frames back to back: the same bytes as the
# two frames made one at a time, as zstd writes its frames.
fresh
want_rc 0 "-zc a b" "$Z" -zc a.fc b.fc
mv out.log both.stz
want_rc 0 "-zc a" "$Z" -zc a.fc
mv out.log a.stz
want_rc 0 "-zc b" "$Z" -zc b.fc
mv out.log b.stz
cat a.stz b.stz | cmp -s - both.stz || fail "-c a b is not frame(a) + frame(b)"
want_rc 0 "zstd -zc a b" zstd -q -zc a.fc b.fc
zstd -q -dc <out.log | cmp -s - <(cat a.fc b.fc) || fail "zstd reference: -zc a b"
pass "-zc f1 f2 writes the frames back to back"

# ... and -d gives back both inputs in order, from the file and from a pipe.
version=$("$Z" info a.stz | awk '/^format version:/ { print $3 }')
[ -n "$version" ] || fail "info prints no format version"
if [ "$version" -ge 2 ]; then
  want_rc 0 "-d of -c f1 f2" "$Z" -dc both.stz
  cmp -s out.log <(cat a.fc b.fc) || fail "-dc of two frames differs from the inputs"
  run bash -c "cat a.stz b.stz | \"$Z\" -d"
  [ "$rc" -eq 0 ] || { cat err.log; fail "cat a.stz b.stz | stepzip -d: exit $rc"; }
  cmp -s out.log <(cat a.fc b.fc) || fail "cat a.stz b.stz | stepzip -d differs from the inputs"
  pass "concatenated frames decode (cat a.stz b.stz | stepzip -d)"
else
  skip "concatenated frames need the v2 decoder (format version $version)"
fi

# --rm with -c keeps the input (zstd too); --rm alone removes it (zstd too).
fresh
cp b.fc z.fc
same_rc "--rm -c" "--rm -q -c z.fc >/dev/null" "--rm -q -c b.fc >/dev/null"
[ -f z.fc ] || fail "zstd reference: --rm -c removed the input"
[ -f b.fc ] || fail "--rm -c removed the input"
same_rc "--rm" "--rm -q z.fc" "--rm -q b.fc"
[ ! -e z.fc ] && [ -f z.fc.zst ] || fail "zstd reference: --rm"
[ ! -e b.fc ] && [ -f b.fc.stz ] || fail "--rm did not remove the input"
fresh
cp b.fc b2.fc
cp b.fc z2.fc
same_rc "--rm -o" "--rm -q -o z2.zst z2.fc" "--rm -q -o b2.stz b2.fc"
[ ! -e z2.fc ] && [ -f z2.zst ] || fail "zstd reference: --rm -o"
[ ! -e b2.fc ] && [ -f b2.stz ] || fail "--rm -o did not remove the input"
pass "--rm never with -c; with -o it removes the input"

# An output over the input itself is refused, the input untouched (zstd too).
fresh
cp b.fc z.fc
same_rc "-o the input" "-q -f -o z.fc z.fc" "-q -f -o b.fc b.fc"
[ "$src" -ne 0 ] || fail "-f -o INPUT INPUT succeeded"
grep -q "over the input file" err.log || fail "-o the input: $(cat err.log)"
cmp -s z.fc b.fc || fail "zstd reference: -o the input changed it"
printf '0 0 0011223344556677\n' | cmp -s - b.fc || fail "-o the input changed it"
want_rc 1 "-d -o the input" "$Z" -q -f -d -o b.fc b.fc
printf '0 0 0011223344556677\n' | cmp -s - b.fc || fail "-d -o the input changed it"
pass "an output over its input is refused"

# Mode, owner and times go from the input to the output, both ways.
fresh
cp a.fc z.fc
chmod 600 a.fc z.fc
touch -d '2020-01-02 03:04:05.123456789' a.fc z.fc
owner_checked=no
if [ "$(id -u)" -eq 0 ] && id nobody >/dev/null 2>&1; then
  chown nobody a.fc z.fc
  owner_checked=yes
fi
same_rc "compress keeps attributes" "-q z.fc" "-q a.fc"
attrs() { stat -c '%a %U %G %Y.%y' "$1" | sed 's/ [0-9-]* \([0-9:.]*\) .*/ \1/'; }
[ "$(attrs z.fc.zst)" = "$(attrs z.fc)" ] || fail "zstd reference: compressed attributes"
[ "$(attrs a.fc.stz)" = "$(attrs a.fc)" ] || fail "compress: $(attrs a.fc.stz) instead of $(attrs a.fc)"
want=$(attrs a.fc)
rm a.fc z.fc
same_rc "decompress keeps attributes" "-q -d z.fc.zst" "-q -d a.fc.stz"
[ "$(attrs z.fc)" = "$want" ] || fail "zstd reference: decompressed attributes"
[ "$(attrs a.fc)" = "$want" ] || fail "decompress: $(attrs a.fc) instead of $want"
cmp -s a.fc "$SRC/corpora/plotter/hershey-grbl.fc" || fail "decompressed bytes differ"
pass "mode, times and (as root: $owner_checked) owner carried to the output"

# 'script' (util-linux) runs a command on a new pseudo-terminal.
have_pty=no
if command -v script >/dev/null && script -qec true /dev/null </dev/null >/dev/null 2>&1; then
  have_pty=yes
fi

# Keyboard input is refused, as zstd refuses it.
if [ "$have_pty" = yes ]; then
  fresh
  for cmd in "" "-d" "-t"; do
    set +e
    zmsg=$(script -qec "zstd $cmd" /dev/null </dev/null); zrc=$?
    smsg=$(script -qec "\"$Z\" $cmd" /dev/null </dev/null); src=$?
    set -e
    [ "$zrc" -ne 0 ] && [[ "$zmsg" == *"stdin is a console"* ]] || fail "zstd reference: console stdin ($cmd)"
    [ "$src" -eq 1 ] && [[ "$smsg" == *"stdin is a console, aborting"* ]] ||
      fail "stepzip $cmd with a console stdin: exit $src, '$smsg'"
  done
  pass "console stdin refused"
else
  skip "console stdin: no pseudo-terminal ('script' from util-linux missing or failing)"
fi

# ---------------------------------------------------------------- habits

# Bundled short options: -zc, -dc, -c19.
fresh
want_rc 0 "compress -c" "$Z" compress -c b.fc
mv out.log ref.stz
want_rc 0 "-zc" "$Z" -zc b.fc
cmp -s out.log ref.stz || fail "-zc differs from compress -c"
want_rc 0 "-dc" "$Z" -dc ref.stz
cmp -s out.log b.fc || fail "-dc differs from the input"
same_rc "-zc / -dc" "-zc b.fc | zstd -dc | cmp -s - b.fc" "-zc b.fc | \"$Z\" -dc | cmp -s - b.fc"
pass "bundled -zc and -dc"

# -# is the level: -19 = -L 19, -1 = -L 1, -c19 bundles.
for level in 1 3 12 19; do
  want_rc 0 "-L $level" "$Z" compress -L "$level" -c a.fc
  mv out.log ref.stz
  want_rc 0 "-$level" "$Z" "-$level" -c a.fc
  cmp -s out.log ref.stz || fail "-$level differs from -L $level"
  want_rc 0 "-c$level" "$Z" "-c$level" a.fc
  cmp -s out.log ref.stz || fail "-c$level differs from -L $level"
done
same_rc "-19" "-19 -c b.fc >/dev/null" "-19 -c b.fc >/dev/null"
want_rc 2 "-20 is beyond the levels" "$Z" -20 -c b.fc
pass "-# levels"

# cat f | stepzip -c, and stepzip with no option at all in a pipe.
same_rc "cat f | -c" "-c <b.fc | zstd -dc | cmp -s - b.fc" "-c <b.fc | \"$Z\" -dc | cmp -s - b.fc"
same_rc "cat f | (nothing)" "<b.fc | zstd -d | cmp -s - b.fc" "<b.fc | \"$Z\" -d | cmp -s - b.fc"
pass "cat f | stepzip -c"

# A bare file name compresses and keeps the input.
fresh
cp b.fc z.fc
same_rc "bare file name" "-q z.fc" "-q b.fc"
[ -f z.fc ] && [ -f z.fc.zst ] || fail "zstd reference: bare file name"
[ -f b.fc ] && [ -f b.fc.stz ] || fail "stepzip b.fc did not write b.fc.stz"
"$Z" -t -q b.fc.stz || fail "b.fc.stz does not verify"
want_rc 2 "a mistyped command" "$Z" compres b.fc
grep -q "neither a command nor a file" err.log || fail "a mistyped command: $(cat err.log)"
pass "stepzip FILE compresses"

# -r DIR: every file under DIR, the same set of outputs as zstd writes; -d -r
# restores them; a run over existing outputs fails as zstd's does. (Unlike
# zstd 1.5, -r skips *.stz when compressing and takes only *.stz with -d.)
for tool in z s; do
  mkdir -p "$tool/d/e"
  cp b.fc "$tool/d/one.fc"
  cp a.fc "$tool/d/e/two.fc"
done
same_rc "-r" "-q -r z/d" "-q -r s/d"
[ "$(cd z && find d -type f | sed 's/\.zst$/.X/' | sort)" = \
  "$(cd s && find d -type f | sed 's/\.stz$/.X/' | sort)" ] || fail "-r wrote other files than zstd -r"
find z s -name '*.fc' -delete
same_rc "-d -r" "-q -d -r z/d" "-q -d -r s/d"
[ "$src" -eq 0 ] || fail "-d -r"
cmp -s s/d/e/two.fc a.fc && cmp -s s/d/one.fc b.fc || fail "-d -r restored other bytes"
same_rc "-r again" "-q -r z/d" "-q -r s/d"
[ "$src" -eq 1 ] || fail "-r over existing outputs succeeded"

pass "-r DIR"

# -t tests every file; a file that is not a frame fails the test.
fresh
"$Z" -q a.fc b.fc
zstd -q a.fc b.fc
same_rc "-t two frames" "-q -t a.fc.zst b.fc.zst" "-q -t a.fc.stz b.fc.stz"
[ "$src" -eq 0 ] || fail "-t a.stz b.stz"
same_rc "-t frame and non-frame" "-q -t a.fc.zst b.fc" "-q -t a.fc.stz b.fc"
[ "$src" -eq 1 ] || fail "-t with a non-frame succeeded"
same_rc "--test two frames" "-q --test a.fc.zst b.fc.zst" "-q --test a.fc.stz b.fc.stz"
[ "$src" -eq 0 ] || fail "--test a.stz b.stz"
want_rc 0 "-t two frames, each reported" "$Z" -t a.fc.stz b.fc.stz
grep -q '^a\.fc\.stz: OK' out.log && grep -q '^b\.fc\.stz: OK' out.log \
  || fail "-t a.stz b.stz did not test both: $(cat out.log)"
want_rc 0 "-t --original" "$Z" -t a.fc.stz --original a.fc
want_rc 1 "-t --original other" "$Z" -t a.fc.stz --original b.fc
grep -q "differ" err.log || fail "-t --original: no 'differ' in $(cat err.log)"
want_rc 2 "--original with two inputs" "$Z" -t a.fc.stz b.fc.stz --original a.fc
pass "-t a.stz b.stz tests both; --original compares"

# -t -r DIR tests every frame under DIR; a damaged one fails the run.
for tool in z s; do mkdir -p "$tool/d/e"; done
cp a.fc.zst z/d/ && cp b.fc.zst z/d/e/
cp a.fc.stz s/d/ && cp b.fc.stz s/d/e/
same_rc "-t -r" "-q -t -r z/d" "-q -t -r s/d"
[ "$src" -eq 0 ] || fail "-t -r DIR"
want_rc 0 "-t -r, each reported" "$Z" -t -r s/d
[ "$(grep -c ': OK' out.log)" -eq 2 ] || fail "-t -r DIR did not test both frames: $(cat out.log)"
head -c 100 a.fc.zst > z/d/e/cut.fc.zst
head -c 100 a.fc.stz > s/d/e/cut.fc.stz
same_rc "-t -r with a truncated frame" "-q -t -r z/d" "-q -t -r s/d"
[ "$src" -eq 1 ] || fail "-t -r with a truncated frame succeeded"
pass "-t -r DIR tests every frame under DIR"

# The verify command keeps its own form (SPEC section 6, relied on by
# scripts): verify INPUT.stz [ORIGINAL], where a second file is the original
# the content is compared with, not a second frame to test.
want_rc 0 "verify X.stz ORIGINAL" "$Z" verify a.fc.stz a.fc
grep -q "identical to a.fc" out.log || fail "verify X.stz ORIGINAL did not compare: $(cat out.log)"
want_rc 1 "verify X.stz OTHER" "$Z" verify a.fc.stz b.fc
grep -q "differ" err.log || fail "verify X.stz OTHER: no 'differ' in $(cat err.log)"
want_rc 1 "verify X.stz Y.stz compares with Y.stz" "$Z" verify a.fc.stz b.fc.stz
grep -q "differ from b.fc.stz" err.log || fail "verify X.stz Y.stz: $(cat err.log)"
want_rc 0 "verify --original" "$Z" verify a.fc.stz --original a.fc
want_rc 2 "verify X.stz ORIGINAL --original" "$Z" verify a.fc.stz a.fc --original a.fc
want_rc 2 "verify with three files" "$Z" verify a.fc.stz b.fc.stz a.fc
pass "verify INPUT.stz [ORIGINAL] compares with ORIGINAL; -t tests every file"

# -T on -d is accepted.
same_rc "-d -T2" "-q -d -T2 -c a.fc.zst >/dev/null" "-q -d -T2 -c a.fc.stz >/dev/null"
[ "$src" -eq 0 ] || fail "-d -T2"
want_rc 0 "-dT2c bundled" "$Z" -dT2 -c a.fc.stz
cmp -s out.log a.fc || fail "-dT2 -c output"
pass "-T accepted by -d"

# -o and -c: the last one given wins (zstd).
fresh
for order in "-c -o" "-o"; do
  rm -f x.zst x.stz
  if [ "$order" = "-c -o" ]; then
    same_rc "-c -o" "-q -c -o x.zst b.fc >c.out" "-q -c -o x.stz b.fc >c.out"
    [ -f x.stz ] && [ ! -s c.out ] || fail "-c -o X: X should be written, stdout empty"
  else
    same_rc "-o -c" "-q -o x.zst -c b.fc >c.out" "-q -o x.stz -c b.fc >c.out"
    [ ! -e x.stz ] && [ -s c.out ] || fail "-o X -c: stdout should be written, not X"
  fi
  [ "$src" -eq 0 ] || fail "$order"
done
# Several inputs into one -o file: zstd asks first (and, without a terminal,
# refuses); stepzip refuses without -f and concatenates with it.
same_rc "-o with two inputs" "-q -o two.zst a.fc b.fc </dev/null" "-q -o two.stz a.fc b.fc"
[ "$src" -ne 0 ] && [ ! -e two.stz ] || fail "-o with two inputs without -f"
want_rc 0 "-o with two inputs -f" "$Z" -q -f -o two.stz a.fc b.fc
"$Z" -q -c a.fc b.fc | cmp -s - two.stz || fail "-f -o two inputs differs from -c"
pass "-o and -c resolved as zstd does"

# Progress on a terminal: bytes read => written and the ratio; -v summary.
if [ "$have_pty" = yes ]; then
  fresh
  prog=$(script -qec "\"$Z\" -z -f a.fc" /dev/null </dev/null | tr '\r' '\n')
  [[ "$prog" =~ a\.fc:\ 100%\ [0-9.]+\ KiB\ =\>\ [0-9.]+\ (B|KiB)\ \([0-9.]+%\) ]] ||
    fail "progress line: $prog"
  pass "progress shows sizes and the ratio"
else
  skip "progress: no pseudo-terminal ('script' from util-linux missing or failing)"
fi
fresh
run zstd -v -f b.fc
grep -q "b.fc.*=>.*b.fc.zst" err.log || fail "zstd reference: -v summary"
want_rc 0 "-v" "$Z" -v -f b.fc
grep -Eq '^b\.fc : [0-9.]+% \([0-9]+ B => [0-9]+ B, b\.fc\.stz\) 16 steps, [0-9.]+ bits/step, profile ' err.log ||
  fail "-v summary: $(cat err.log)"
want_rc 0 "-d -v" "$Z" -d -v -f b.fc.stz
grep -Eq '^b\.fc\.stz : [0-9.]+% \([0-9]+ B => 21 B, b\.fc\) profile ' err.log || fail "-d -v summary: $(cat err.log)"
pass "-v summary line"

# An input no format fits: the best guess and where it failed.
printf '0 0 0011\n5 5 0182\n' > bad.fc
want_rc 1 "unknown format" "$Z" bad.fc
grep -q "looks most like freeman: bad.fc:2:7: '8' is not a Freeman code 0-7" err.log ||
  fail "unknown format message: $(cat err.log)"
[ ! -e bad.fc.stz ] || fail "unknown format left an output"
pass "an unrecognized input names the best guess and the place"

echo "habits: $passed passed, $skipped skipped"
