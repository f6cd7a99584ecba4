#!/usr/bin/env bash
# tests/install/runtime_only.sh SOURCE_DIR -- what an engine team does with looptess:
#   1. configure the source tree with -DLOOPTESS_TOOLCHAIN=OFF and OpenSubdiv,
#      TinyGLTF, Draco, Embree, GLM and stb disabled (CMAKE_DISABLE_FIND_PACKAGE_*),
#      build, run the tests that build has, install;
#   2. check that nothing looked for those packages (no cache entry of theirs; CMake
#      warns that the CMAKE_DISABLE_FIND_PACKAGE_* it was given went unused) and
#      that no installed targets file names an absolute path;
#   3. move the install to another prefix, build tests/install/engine against it
#      with find_package(looptess COMPONENTS runtime vulkan), and run it on a baked
#      file of the tests: load, evaluate on the CPU, draw headless.
# Exit 0 when every step passed. ctest: Install.RuntimeOnlyBuildInstallsAndAnEngineDraws.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$1" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/looptess_runtime_only.XXXXXX")
trap 'rm -rf "$work"' EXIT
export TMPDIR=$work   # what the nested ctest writes stays in here
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
tool_packages=(OpenSubdiv TinyGLTF draco embree glm stb)
disabled=()
for p in "${tool_packages[@]}"; do disabled+=("-DCMAKE_DISABLE_FIND_PACKAGE_$p=ON"); done

cmake -S "$src" -B "$work/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DLOOPTESS_TOOLCHAIN=OFF \
  -DLOOPTESS_TESTS=ON -DLOOPTESS_EXAMPLES=ON "${disabled[@]}" >/dev/null
if grep -E -i "^(OpenSubdiv|TinyGLTF|draco|embree|glm|stb)[_A-Za-z]*(_DIR|_LIBRARY|_INCLUDE_DIR)?:" \
     "$work/build/CMakeCache.txt" | grep -v -E "NOTFOUND$|^[A-Za-z]+_DIR:PATH=$"; then
  echo "runtime_only.sh: a LOOPTESS_TOOLCHAIN=OFF configure looked for a tool chain package (above)" >&2
  exit 1
fi
cmake --build "$work/build" >/dev/null
ctest --test-dir "$work/build" --output-on-failure -j 2 | tail -n 3
cmake --install "$work/build" --prefix "$work/installed" >/dev/null

"$here/no_absolute_paths.sh" "$work/installed"
ls "$work"/installed/lib/cmake/looptess/ | grep -q baker && { echo "runtime_only.sh: the baker was installed" >&2; exit 1; }

mv "$work/installed" "$work/moved"   # relocatable: nothing may point at the first prefix
cmake -S "$here/engine" -B "$work/engine" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/moved" "${disabled[@]}" >/dev/null
cmake --build "$work/engine" >/dev/null
"$work/engine/engine_consumer" "$src/tests/data/golden/loop_icos_semisharp.glb"
