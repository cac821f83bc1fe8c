#!/usr/bin/env bash
# Installs the Debian bookworm packages snee needs (only when some are missing) and builds
# snee in Release mode in build/. Safe to run again: with everything present it only builds.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# Keep in sync with docs/dependencies.md.
packages=(
  cmake make g++ pkg-config
  libembree-dev libopenimageio-dev libtbb-dev libxsimd-dev xtl-dev nlohmann-json3-dev
  libcli11-dev librandom123-dev libtinyobjloader-dev libtinygltf-dev assimp-testmodels libgtest-dev libbenchmark-dev
  libopenmpi-dev openmpi-bin
  fonts-dejavu-core
  clang-format
  clang libclang-rt-dev
)

missing=()
for package in "${packages[@]}"; do
  if [[ "$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null)" != "install ok installed" ]]; then
    missing+=("$package")
  fi
done

if ((${#missing[@]} > 0)); then
  if [[ $(id -u) -eq 0 ]]; then
    as_root=()
  elif command -v sudo >/dev/null; then
    as_root=(sudo)
  else
    echo "error: missing packages (${missing[*]}); run as root or install sudo" >&2
    exit 1
  fi
  echo "installing ${missing[*]}" >&2
  "${as_root[@]}" apt-get update -qq
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release --log-level=WARNING >/dev/null
cmake --build build -j"$(nproc)"
