#!/usr/bin/env bash
# The GPU bundle's entry point (scripts/gpu-bundle.sh writes it as run.sh): the
# Vulkan tests and the render benchmarks on this machine's Vulkan device, with the
# bundle's own libraries, loader, validation layer and data, from any folder.
#
#   run.sh [--tests | --bench] [REPORT_DIR]     (default: both, into ./gpu-report)
#
# REPORT_DIR gets: device.txt (the devices the loader sees), test_vulkan.xml and .log
# (GoogleTest), bench_render.json, .txt and PNGs (spot, the Duck; each path),
# bench_lod.txt, looprender.json and auto.png (DrawPath::Auto's choice on spot).
# Environment: LOOPTESS_DEVICE picks a device by a part of its name (tests,
# looprender); VK_DRIVER_FILES a driver manifest (NVIDIA's in a container, if unset
# and present, is taken). Exit status: the tests', else 0.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
mode=all
case "${1:-}" in --tests) mode=tests; shift ;; --bench) mode=bench; shift ;; esac
report=$(mkdir -p "${1:-gpu-report}" && cd "${1:-gpu-report}" && pwd)

export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export VK_LAYER_PATH="$here/layers"
export LOOPTESS_TEST_DATA="$here/data" LOOPTESS_CORPUS_DIR="$here/data/corpus"
export LOOPBAKE_EXE="$here/bin/loopbake" LOOPRENDER_EXE="$here/bin/looprender"
nvidia=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -z "${VK_DRIVER_FILES:-}" ] && [ -z "${VK_ICD_FILENAMES:-}" ] && [ -f "$nvidia" ]; then export VK_DRIVER_FILES=$nvidia; fi

device=()
[ -n "${LOOPTESS_DEVICE:-}" ] && device=(--device "$LOOPTESS_DEVICE")
cd "$report"
{ echo "bundle: $here"; uname -a; ldd --version 2>&1 | head -1; "$here/bin/looprender" --version; } > device.txt

status=0
if [ "$mode" != bench ]; then
  echo "run.sh: test_vulkan (log: $report/test_vulkan.log)"
  "$here/bin/test_vulkan" --gtest_output="xml:$report/test_vulkan.xml" > test_vulkan.log 2>&1
  status=$?
  grep -E "^\[ (vulkan|figures) |^\[  (PASSED|FAILED) |tests? ran" test_vulkan.log
  echo "run.sh: test_vulkan exit status $status"
fi
if [ "$mode" != tests ]; then
  scratch=$(mktemp -d)
  "$here/bin/loopbake" "$here/data/corpus/meshes/spot.obj" -o "$scratch/spot.glb" >/dev/null
  echo "run.sh: looprender --path auto (DrawPath::Auto's trials)"
  "$here/bin/looprender" "$scratch/spot.glb" "${device[@]}" --tess 8 --frames 8 --png auto.png --json looprender.json -v \
    2>&1 | tee looprender.log | grep -E "path|GPU ms"
  rm -rf "$scratch"
  mkdir -p png
  echo "run.sh: bench_render (spot and the Duck, F = 8 and 32)"
  "$here/bin/bench_render" --corpus "$here/data/corpus" --mesh spot --mesh duck --factor 8 --factor 32 --frames 5 \
    --json bench_render.json --save png > bench_render.txt 2> bench_render.log
  echo "run.sh: bench_render exit status $?; bench_lod (spot, 1, 2 and 4 px)"
  "$here/bin/bench_lod" --corpus "$here/data/corpus" --mesh spot --frames 3 > bench_lod.txt 2> bench_lod.log
  echo "run.sh: bench_lod exit status $?"
  cat bench_render.txt bench_lod.txt
fi
echo "run.sh: report in $report"
exit $status
