#!/usr/bin/env bash
# Prints the SHA-1 of the pixels (not the metadata) of small renders of the default scene, the
# paper grid and the furnaces, for every integrator and schedule: one line per render. Refactors
# that promise unchanged images diff this output before and after (docs/architecture.md).
# Needs iinfo (Debian package openimageio-tools). Usage: scripts/pixel-hashes.sh [BUILD_DIR]
# [SIMD_LEVEL]; with a level (sse4.2, avx2, avx512) every render uses its kernels (--simd), so
# the outputs for two levels must be identical too.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

snee=${1:-build}/apps/snee
simd=()
if [[ -n "${2:-}" ]]; then simd=(--simd "$2"); fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source scripts/grid-scenes.sh
scenes=(default furnace-sphere furnace-bunny furnace-sphere-null "${grid_scenes[@]}")
for scene in "${scenes[@]}"; do
  for integrator in pt snee sla; do
    for schedule in local megakernel global; do
      image="$out/$scene-$integrator-$schedule.exr"
      "$snee" render "builtin:$scene" --integrator "$integrator" --schedule "$schedule" \
        --spp 4 --resolution 24x24 --threads 2 "${simd[@]}" -q -o "$image" >/dev/null
      echo "$scene $integrator $schedule $(iinfo --hash "$image" | sed -n 's/.*SHA-1: //p')"
    done
  done
done
