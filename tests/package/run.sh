#!/usr/bin/env bash
# Installs the built stepzip into a scratch prefix, then builds and runs an
# outside consumer that finds it with find_package(stepzip).
set -euo pipefail
src=$1
build=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
cmake -S "$src/tests/package/consumer" -B "$work/consumer" \
      -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/consumer-configure.log"
cmake --build "$work/consumer" >"$work/consumer-build.log"
"$work/consumer/consumer"
