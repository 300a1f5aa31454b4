#!/usr/bin/env bash
# Configures and builds geohybrid (Release) into build/ ; extra arguments go to cmake.
# GEOHYBRID_BUILD_DIR: another build directory; GEOHYBRID_BUILD_TARGET: that target only.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${GEOHYBRID_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" > "$build.configure.log" 2>&1 \
  || { cat "$build.configure.log"; exit 1; }
cmake --build "$build" -j "$(nproc)" ${GEOHYBRID_BUILD_TARGET:+--target "$GEOHYBRID_BUILD_TARGET"}
