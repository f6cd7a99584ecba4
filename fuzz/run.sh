#!/usr/bin/env bash
# fuzz/run.sh BUILD_DIR SECONDS [NAME...] -- makes the seed corpora, then runs each
# fuzzer (default: asset obj gltf evaluate edits scene, and usd when built) for SECONDS. BUILD_DIR is a LOOPTESS_FUZZ
# build with the `fuzz` and `loopbake` targets built (scripts/dev.sh fuzz does this).
#
# Layout under BUILD_DIR (nothing is written to the source tree):
#   fuzz-seeds/NAME/      seeds, regenerated every run from tests/data, the shared
#                         corpus, shapes baked at depth 2 and Draco GLBs
#   fuzz-corpus/NAME/     what libFuzzer found interesting; kept across runs
#   fuzz-artifacts/NAME/  crash-*, timeout-*, oom-* inputs (turn each into a
#                         regression test: tests/data/fuzz/README.md)
#   fuzz-logs/NAME.log    libFuzzer's output, ending with its final stats
# Prints one line per fuzzer (executions, corpus size, artifacts); exits 1 if any
# fuzzer found something.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "$1" && pwd)
seconds=$2
shift 2
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  names=(asset obj gltf evaluate edits scene)
  [ -x "$build/fuzz/fuzz_usd" ] && names+=(usd)   # built with USD input (cmake/Usd.cmake)
fi
corpus=$src/tests/data/corpus

seeds=$build/fuzz-seeds
rm -rf "$seeds"
mkdir -p "$seeds"/{asset,obj,gltf,evaluate,edits,scene,usd,baked} "$build"/fuzz-logs

# Up to 64 KB: larger seeds would only be truncated to -max_len.
small() { find "$@" -maxdepth 1 -type f -size -64k 2>/dev/null || true; }
small "$src/tests/data" "$src/tests/data/bad" "$corpus/opensubdiv-loop" | grep -v '\.md$' |
  xargs -r cp -n -t "$seeds/obj"
shapes=("$src"/tests/data/loop_*.obj)
[ -n "$corpus" ] && shapes+=("$corpus"/opensubdiv-loop/loop_*.obj)
for obj in "${shapes[@]}"; do   # baked assets: depth 2 keeps them small; compressed (the default) and plain
  "$build/bin/loopbake" "$obj" -o "$seeds/baked/$(basename "$obj" .obj).glb" --max-depth 2 2>/dev/null || true
  "$build/bin/loopbake" "$obj" -o "$seeds/baked/$(basename "$obj" .obj)_plain.glb" --max-depth 2 --compress none \
    2>/dev/null || true
done
# A scene whose cage primitives carry TEXCOORD_1 and COLOR_0 (normalized bytes).
"$build/bin/loopbake" "$src/tests/data/scenes/vertex_attributes.gltf" -o "$seeds/baked/vertex_attributes.glb" \
  --max-depth 2 2>/dev/null || true
# Scenes for looprender's scene reader: images, materials, skins, animations.
for s in scenes/BoxTextured.gltf scenes/texture_formats.gltf real/fox.glb; do
  "$build/bin/loopbake" "$src/tests/data/$s" -o "$seeds/scene/$(basename "${s%.*}").glb" --max-depth 1 2>/dev/null || true
done
small "$seeds/baked" | xargs -r cp -n -t "$seeds/asset"
small "$seeds/baked" | xargs -r cp -n -t "$seeds/evaluate"
small "$seeds/baked" | xargs -r cp -n -t "$seeds/scene"
small "$seeds/baked" | xargs -r cp -n -t "$seeds/gltf"
[ -n "$corpus" ] && cp "$corpus"/gltf/* "$seeds/gltf/"
for shape in loop_tetrahedron loop_icosahedron loop_cube_creases0; do
  obj=${corpus:-/nonexistent}/opensubdiv-loop/$shape.obj
  [ -f "$obj" ] || continue
  "$build/fuzz/make_draco_seed" "$obj" "$seeds/gltf/draco_eb_$shape.glb"
  "$build/fuzz/make_draco_seed" "$obj" "$seeds/gltf/draco_seq_$shape.glb" sequential
done
cp "$src"/fuzz/seeds/gltf/* "$seeds/gltf/"
cp "$src"/fuzz/seeds/edits/* "$seeds/edits/"
small "$src/tests/data/usd" "$src/tests/data/usd/bad" | grep '\.usda$' | xargs -r cp -n -t "$seeds/usd"
for name in asset obj gltf evaluate edits scene usd; do   # past findings seed their fuzzer again
  find "$src/tests/data/fuzz" -maxdepth 1 -type f -name "${name}_*" -exec cp -t "$seeds/$name" {} + 2>/dev/null || true
done

found=0
for name in "${names[@]}"; do
  case "$name" in
    obj) dict=obj.dict; maxlen=65536 ;;
    gltf) dict=gltf.dict; maxlen=200000 ;;   # the Duck seeds (120 and 160 KB) stay whole
    asset|evaluate) dict=gltf.dict; maxlen=65536 ;;
    scene) dict=gltf.dict; maxlen=131072 ;;   # the baked Fox with its texture
    edits) dict=gltf.dict; maxlen=8192 ;;
    usd) dict=usd.dict; maxlen=65536 ;;
    *) echo "fuzz/run.sh: unknown fuzzer '$name'" >&2; exit 1 ;;
  esac
  mkdir -p "$build/fuzz-corpus/$name" "$build/fuzz-artifacts/$name"
  log=$build/fuzz-logs/$name.log
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: 2 GB is a finding.
  "$build/fuzz/fuzz_$name" "$build/fuzz-corpus/$name" "$seeds/$name" -dict="$src/fuzz/$dict" \
    -max_total_time="$seconds" -max_len=$maxlen -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$build/fuzz-artifacts/$name/" -print_final_stats=1 >"$log" 2>&1 || true
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  artifacts=$(find "$build/fuzz-artifacts/$name" -type f | wc -l)
  echo "fuzz_$name: $seconds s, $execs executions, corpus $(ls "$build/fuzz-corpus/$name" | wc -l) inputs, $artifacts artifact(s)"
  [ "$artifacts" -eq 0 ] || found=1
done
[ "$found" -eq 0 ] || echo "fuzz: artifacts in $build/fuzz-artifacts (see tests/data/fuzz/README.md)" >&2
exit $found
