#!/usr/bin/env bash
# Packs what checks a build on a GPU into one folder that runs on any x86-64 Linux
# with glibc 2.36 (Debian 12's) or newer and a Vulkan driver, with nothing else
# installed: a GPU CI runner's, or a workstation's.
#
#   scripts/gpu-bundle.sh BUILD_DIR OUT_DIR      (scripts/dev.sh gpu-bundle calls it)
#
#   OUT_DIR/run.sh [--tests|--bench] [REPORT_DIR]   the GPU tests and the benchmarks
#   OUT_DIR/bin/      test_vulkan, looprender, loopbake, bench_render, bench_lod (stripped)
#   OUT_DIR/lib/      the shared libraries they load that a bare system lacks, and the
#                     Vulkan loader, unpacked from Debian's libvulkan1
#   OUT_DIR/layers/   VK_LAYER_KHRONOS_validation, unpacked from Debian's
#                     vulkan-validationlayers (the tests run with it on)
#   OUT_DIR/data/     the test data they read (tests/data/corpus, two scenes of
#                     tests/data/real, with their licences)
#
# The folder stays under 48 MiB (checked here). Where Debian's packages cannot be
# downloaded (no apt sources), the installed copies of the same packages are taken.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:?usage: scripts/gpu-bundle.sh BUILD_DIR OUT_DIR}
out=${2:?usage: scripts/gpu-bundle.sh BUILD_DIR OUT_DIR}
binaries=("$build/tests/vulkan/test_vulkan" "$build/bin/looprender" "$build/bin/loopbake" "$build/bench/bench_render"
          "$build/bench/bench_lod")
for b in "${binaries[@]}"; do [ -x "$b" ] || { echo "gpu-bundle: $b is missing: build it first" >&2; exit 1; }; done

rm -rf "$out"
mkdir -p "$out/bin" "$out/lib" "$out/layers" "$out/data/real"
for b in "${binaries[@]}"; do strip -s -o "$out/bin/$(basename "$b")" "$b"; done

# Shared libraries but glibc's own (the system's: libc, libm, the dynamic loader)
# and the Vulkan loader (Debian's package, below).
for b in "${binaries[@]}"; do ldd "$b"; done | awk '$3 ~ /^\// {print $3}' | sort -u | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|ld-linux*|libvulkan.so.*) ;;
    *) cp -L "$lib" "$out/lib/" && strip --strip-unneeded "$out/lib/$(basename "$lib")" ;;
  esac
done

# The Vulkan loader and the validation layer from Debian's packages.
debs=$(mktemp -d)
trap 'rm -rf "$debs"' EXIT
if (cd "$debs" && apt-get download -q libvulkan1 vulkan-validationlayers >/dev/null 2>&1); then
  for deb in "$debs"/*.deb; do dpkg-deb -x "$deb" "$debs/root"; done
  packaged=$debs/root
  echo "gpu-bundle: the Vulkan loader and validation layer from $(cd "$debs" && ls ./*.deb | xargs -n1 basename | tr '\n' ' ')"
else
  packaged=""
  echo "gpu-bundle: apt-get download failed: the installed libvulkan1 and vulkan-validationlayers are taken"
fi
arch=usr/lib/x86_64-linux-gnu
cp -L "${packaged:-}/$arch/libvulkan.so.1" "$out/lib/libvulkan.so.1"
cp -L "${packaged:-}/$arch/libVkLayer_khronos_validation.so" "$out/layers/"
# The manifest names its library relative to itself (a path with a separator is).
sed 's#"library_path": *"[^"]*"#"library_path": "./libVkLayer_khronos_validation.so"#' \
  "${packaged:-}/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json" > "$out/layers/VkLayer_khronos_validation.json"

cp -rL "$root/tests/data/corpus" "$out/data/"
cp "$root/tests/data/real/fox.glb" "$root/tests/data/real/robotexpressive.glb" "$root/tests/data/real/README.md" "$out/data/real/"
cp -r "$root/tests/data/real/licenses" "$out/data/real/"
cp "$root/scripts/gpu-bundle-run.sh" "$out/run.sh"
chmod +x "$out/run.sh"

bytes=$(du -sb "$out" | cut -f1)
echo "gpu-bundle: $out: $(du -sh "$out" | cut -f1) ($bytes bytes)"
if [ "$bytes" -gt $((48 * 1024 * 1024)) ]; then
  echo "gpu-bundle: larger than 48 MiB" >&2
  exit 1
fi
