#!/usr/bin/env bash
# The quick start and CI entry point. On a fresh Debian 12 machine:
#   scripts/dev.sh sample   install packages, build everything, bake the bundled
#                           sample (tests/data/spot.obj) and capture it on the CPU
#   scripts/dev.sh test     install packages, build everything, run the tests
# BUILD_DIR (default: build) chooses the build directory.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
mode=${1:-}
case "$mode" in sample|test) ;; *) echo "usage: scripts/dev.sh sample|test" >&2; exit 1 ;; esac

"$root/scripts/setup-debian.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build"

if [ "$mode" = sample ]; then
  out="$build/sample"
  mkdir -p "$out"
  "$build/baker/loopbake" "$root/tests/data/spot.obj" -o "$out/spot.glb" -v
  "$build/runtime/looprender" --cpu "$out/spot.glb" --tess 8 --capture "$out/spot.ply" -v
  echo "sample: $out/spot.glb (baked asset) and $out/spot.ply (CPU capture at factor 8)"
else
  ctest --test-dir "$build" --output-on-failure -j "$(nproc)"
fi
