#!/usr/bin/env bash
# Faults: a full disk, unreadable inputs, an existing output, a signal in the
# middle of the work. For compress, decompress, interpolate and segment each
# failure must leave no output file (and no temporary file), the input
# untouched, exactly one line on stderr, and a non-zero exit code. A check
# that cannot run here says "skip:" and why; a command that finishes before
# its signal arrives is a failure (the signal check did not happen).
# Usage: bash faults.sh <stepzip-binary> <source-dir>
set -euo pipefail
Z=$(realpath "$1")
SRC=$(realpath "$2")
W=$(mktemp -d)
trap 'chmod -R u+rwx "$W" 2>/dev/null; rm -rf "$W"' EXIT
cd "$W"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# no_leftovers "what": no output and no temporary file in the work directory.
no_leftovers() {
    local left
    left=$(find . -maxdepth 2 \( -name '.*.stepzip-*' -o -name 'out.*' \) -print)
    [ -z "$left" ] || fail "$1: left behind: $left"
    rm -f ./.*.stepzip-* out.*
}
# refuse "what" pattern command... : exit status non-zero (1 unless a signal),
# exactly one stderr line matching pattern, inputs unchanged, nothing left.
refuse() {
    local what=$1 pattern=$2 rc=0; shift 2
    "$@" >stdout.log 2>err.log || rc=$?
    [ $rc -ne 0 ] || fail "$what: exit 0"
    [ $rc -eq 1 ] || fail "$what: exit $rc, expected 1"
    [ "$(wc -l <err.log)" -eq 1 ] || { fail "$what: stderr is not one line"; cat err.log; }
    grep -q -- "$pattern" err.log || { fail "$what: message lacks '$pattern'"; cat err.log; }
    sha256sum -c --quiet inputs.sum || fail "$what: an input changed"
    no_leftovers "$what"
}

cp "$SRC/tests/golden/plotter.fc" in.fc
"$Z" compress -q in.fc -o in.stz || fail "setup: compress"
cp "$SRC/corpora/samples/plot.gcode" in.gcode
mkdir dir.fc dir.stz
sha256sum in.fc in.stz in.gcode >inputs.sum

# Each command, with its arguments before the input and the output option.
cmds=("compress" "decompress" "interpolate --profile grbl" "segment --to gcode")
inputs=(in.fc in.stz in.gcode in.fc)
for i in "${!cmds[@]}"; do
    read -r -a c <<<"${cmds[$i]}"
    in=${inputs[$i]}
    name=${c[0]}
    # A full disk, as a named output and through standard output.
    refuse "$name -o /dev/full" "No space left" "$Z" "${c[@]}" "$in" -o /dev/full
    refuse "$name -o /dev/full -f" "No space left" "$Z" "${c[@]}" "$in" -o /dev/full -f
    refuse "$name -c >/dev/full" "No space left" sh -c '"$@" >/dev/full' sh "$Z" "${c[@]}" "$in" -c
    [ -c /dev/full ] || fail "$name: /dev/full is no longer a device"
    # Inputs that cannot be read: missing, a directory.
    refuse "$name missing input" "missing" "$Z" "${c[@]}" missing -o out.x
    refuse "$name directory input" "directory" "$Z" "${c[@]}" "dir.${in##*.}" -o out.x
    # An existing output without -f is refused and left as it was.
    echo keep >keep.existing
    refuse "$name existing output" "already exists" "$Z" "${c[@]}" "$in" -o keep.existing
    echo keep | cmp -s - keep.existing || fail "$name: existing output was touched"
    rm -f keep.existing
    # An output directory that does not exist.
    refuse "$name output in a missing directory" "nodir" "$Z" "${c[@]}" "$in" -o nodir/out.x
done

# An input without read permission. Tests often run as root, where the
# permission bits do not stop reading: then run the command as an
# unprivileged user when the system has one and setpriv, else skip.
cp in.fc locked.fc
chmod 000 locked.fc
sha256sum in.fc in.stz in.gcode >inputs.sum
as_user=()
if [ "$(id -u)" -eq 0 ]; then
    if command -v setpriv >/dev/null && id nobody >/dev/null 2>&1; then
        as_user=(setpriv --reuid=nobody --regid="$(id -g nobody)" --clear-groups)
        chmod 755 "$W"
    fi
fi
if [ "$(id -u)" -ne 0 ] || [ ${#as_user[@]} -gt 0 ]; then
    for c in compress decompress "interpolate --profile grbl" "segment --to gcode"; do
        read -r -a cc <<<"$c"
        refuse "${cc[0]} unreadable input" "Permission denied" "${as_user[@]}" "$Z" "${cc[@]}" locked.fc -c
    done
else
    echo "skip: unreadable input (running as root without setpriv or user 'nobody')"
fi
chmod 600 locked.fc
rm -f locked.fc
chmod 700 "$W"

# A signal in the middle of the work removes the temporary output. A random
# walk of a few million steps keeps each command busy for a while.
table=$(printf '01234567%.0s' {1..32})
{ printf '0 0 '; head -c 1000000 /dev/urandom | tr '\000-\377' "$table"; echo; } >big.fc
[ "$(wc -c <big.fc)" -eq 1000005 ] || fail "setup: big.fc has the wrong size"
# Level 10: the step model, whose decoder takes long enough to be interrupted
# (the fast levels' table blocks decode a random walk too quickly).
"$Z" compress -q big.fc -o big.stz -L 10 || fail "setup: compress big.fc"
{
    echo "G0 X0 Y0"
    for k in $(seq 1 200); do echo "G1 X$((k * 5000)) Y$(((k % 2) * 3000000))"; done
} >big.gcode
sha256sum big.fc big.stz big.gcode >inputs.sum
set -m  # background jobs keep the default SIGINT disposition
sig_cmds=("compress big.fc -L 19" "decompress big.stz" "interpolate --profile eval4 big.gcode"
          "segment --to json --segmenter optimal big.fc")
for c in "${sig_cmds[@]}"; do
    read -r -a cc <<<"$c"
    for sig in INT TERM; do
        what="${cc[0]} SIG$sig"
        "$Z" "${cc[@]}" -o out.x 2>err.log &
        pid=$!
        # Wait until the work is under way, then interrupt it: compress and
        # decompress open their temporary output first (wait for it, at most
        # half a second, and signal at once: decompression takes a fraction
        # of a second); interpolate and segment write theirs at the end.
        had_temp=no
        case ${cc[0]} in
            compress | decompress)
                for _ in $(seq 1 50); do
                    [ -n "$(find . -maxdepth 1 -name '.out.x.stepzip-*' -print -quit)" ] && { had_temp=yes; break; }
                    sleep 0.01
                done ;;
        esac
        [ $had_temp = yes ] || sleep 0.1
        kill -s "$sig" "$pid" 2>/dev/null || true
        rc=0
        wait "$pid" || rc=$?
        if [ $rc -eq 0 ]; then
            fail "$what: finished before the signal arrived (the check did not run; make the input larger)"
            rm -f out.x
            continue
        fi
        [ $rc -gt 128 ] || fail "$what: exit $rc, expected death by the signal"
        case ${cc[0]} in  # these two open their output before the work starts
            compress | decompress) [ $had_temp = yes ] || fail "$what: no temporary file seen" ;;
        esac
        [ "$(wc -l <err.log)" -le 1 ] || { fail "$what: stderr is more than one line"; cat err.log; }
        sha256sum -c --quiet inputs.sum || fail "$what: an input changed"
        no_leftovers "$what"
        [ ! -e out.x ] || fail "$what: output left"
    done
done
set +m

if [ $fails -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
fi
echo "faults: all checks passed"
