#!/usr/bin/env bash
# Configures (once) and builds stc into build/.  Extra arguments go to cmake
# at configure time, e.g. tools/build.sh -DSTC_SANITIZE=ON (use another
# BUILD_DIR for that: BUILD_DIR=build-asan tools/build.sh -DSTC_SANITIZE=ON).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@"
fi
cmake --build "$BUILD_DIR" --parallel "$(nproc)"
