#!/usr/bin/env bash
# pip install --no-build-isolation . from a copy of the source tree into a
# fresh virtual environment (with the system's numpy, setuptools, wheel and
# no package index), then the Python tests against the installed package.
# Usage: pip_install.sh SOURCE_DIR WORK_DIR PYTHON
# Exit 77 (skipped, with the reason) only when a virtual environment cannot
# be made on this system.
set -euo pipefail
SRC=$(realpath "$1")
WORK=$2
PY=$3

rm -rf "$WORK"
mkdir -p "$WORK"
WORK=$(realpath "$WORK")
trap 'rm -rf "$WORK/src" "$WORK/venv"' EXIT

if ! "$PY" -m venv --system-site-packages "$WORK/venv" >"$WORK/venv.log" 2>&1; then
  echo "skip: '$PY -m venv' cannot make a virtual environment here (install python3-venv):"
  tail -n 3 "$WORK/venv.log"
  exit 77
fi
VPY="$WORK/venv/bin/python"

# A copy of the sources without build trees, as a user's checkout is.
mkdir "$WORK/src"
tar -C "$SRC" --exclude='./build*' --exclude='./.git' --exclude='*.egg-info' -cf - . |
  tar -C "$WORK/src" -xf -

# Paths below the copy are hashed relative to it, so ccache (used by setup.py
# when installed) finds earlier builds of the same sources from other copies.
export CCACHE_BASEDIR="$WORK/src" CCACHE_NOHASHDIR=1
if ! "$VPY" -m pip install --no-build-isolation --no-index "$WORK/src" >"$WORK/pip.log" 2>&1; then
  tail -n 40 "$WORK/pip.log"
  echo "FAIL: pip install --no-build-isolation ."
  exit 1
fi

# The installed package, not the source tree or a build directory.
cd "$WORK"
where=$(env -u PYTHONPATH "$VPY" -c 'import stepzip; print(stepzip.__file__)')
case "$where" in
  "$WORK/venv/"*) ;;
  *) echo "FAIL: stepzip imported from $where, not from the virtual environment"; exit 1 ;;
esac
for f in __init__.py _stepzip.pyi py.typed; do
  [ -f "$(dirname "$where")/$f" ] || { echo "FAIL: $f is not installed"; exit 1; }
done

cp "$SRC/tests/python/test_stepzip.py" "$WORK/"
if ! env -u PYTHONPATH STEPZIP_SOURCE_DIR="$SRC" "$VPY" -m unittest test_stepzip 2>"$WORK/test.log"; then
  tail -n 40 "$WORK/test.log"
  echo "FAIL: the tests against the installed package"
  exit 1
fi
tail -n 3 "$WORK/test.log"
echo "pip install --no-build-isolation . and its tests: OK"
