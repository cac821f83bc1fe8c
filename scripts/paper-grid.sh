#!/usr/bin/env bash
# Reproduces the SNEE paper's grid (docs/results.md): for the sphere and the bunny under a
# directional, cone and environment light with GGX roughness 0.2, 0.04 and a smooth interface,
# `snee compare` renders pt and snee at equal time against a long snee reference, three times
# with independent seeds (the reference is made once, by the first run). Writes
# out/grid/<scene>/run<N>/ (EXRs, compare.json, contact-sheet.png), prints a markdown table
# of the median efficiency ratios (scripts/grid-table.py), and writes docs/results.md's pictures:
# each scene's first contact sheet at 3x (docs/images/grid/) and the overview of all 18.
# Usage: scripts/paper-grid.sh [SECONDS] [REF_SPP] [RES] [RUNS]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

seconds=${1:-4}
reference_spp=${2:-2048}
resolution=${3:-48x48}
runs=${4:-3}
source scripts/grid-scenes.sh
for scene in "${grid_scenes[@]}"; do
  dir="out/grid/$scene"
  for run in $(seq 1 "$runs"); do
    reference=()
    [[ $run -gt 1 ]] && reference=(--reference "$dir/run1/reference.exr")
    build/apps/snee compare "builtin:$scene" --time "$seconds" --reference-spp "$reference_spp" \
      --resolution "$resolution" --seed "$run" "${reference[@]}" -o "$dir/run$run" -q >/dev/null
  done
  echo "done $scene" >&2
done
python3 scripts/grid-table.py out/grid
sheets=()
for scene in "${grid_scenes[@]}"; do
  oiiotool "out/grid/$scene/run1/contact-sheet.png" --resize:filter=box 300% \
    -o "docs/images/grid/$scene.png"
  sheets+=("out/grid/$scene/run1/contact-sheet.png")
done
oiiotool "${sheets[@]}" --mosaic:pad=8 3x6 --resize:filter=box 200% -o docs/images/grid-overview.png
