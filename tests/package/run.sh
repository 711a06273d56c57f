#!/usr/bin/env bash
# Installs the built stepzip into a scratch prefix, then builds and runs
# outside consumers against the installed tree only:
#  - a C++ project that finds it with find_package(stepzip);
#  - a C program compiled with `pkg-config --cflags --libs stepzip`.
# Usage: bash run.sh <source-dir> <build-dir> <work-dir> [C compiler]
set -euo pipefail
src=$1
build=$2
work=$3
cc=${4:-cc}
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
cmake -S "$src/tests/package/consumer" -B "$work/consumer" \
      -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/consumer-configure.log"
cmake --build "$work/consumer" >"$work/consumer-build.log"
"$work/consumer/consumer"

# pkg-config finds the installed stepzip.pc (it locates its prefix from its
# own directory, so the scratch prefix works); nothing from the source tree.
pcdir=$(dirname "$(find "$work/prefix" -name stepzip.pc | head -1)")
[ -f "$pcdir/stepzip.pc" ] || { echo "stepzip.pc was not installed"; exit 1; }
export PKG_CONFIG_PATH="$pcdir${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
flags=$(pkg-config --cflags --libs stepzip)
echo "pkg-config --cflags --libs stepzip: $flags"
case "$flags" in
  *"$src/include"*) echo "pkg-config flags point into the source tree"; exit 1 ;;
esac
[ "$(pkg-config --modversion stepzip)" = "$(sed -n 's/^project(stepzip VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")" ] \
    || { echo "pkg-config version differs from the project's"; exit 1; }
# shellcheck disable=SC2086
"$cc" -std=c99 -Wall -Wextra -pedantic -Werror -o "$work/c_consumer" \
      "$src/tests/package/c_consumer/main.c" $flags >"$work/c-consumer-build.log" 2>&1 \
    || { cat "$work/c-consumer-build.log"; exit 1; }
LD_LIBRARY_PATH="$(pkg-config --variable=libdir stepzip)${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
    "$work/c_consumer"
