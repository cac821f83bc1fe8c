#!/usr/bin/env bash
# Reproduces the SNEE paper's grid (docs/results.md): for the sphere and the bunny under a
# directional, cone and environment light with GGX roughness 0.2, 0.04 and a smooth interface,
# `snee compare` renders pt and snee at equal time against a long snee reference. Writes
# out/grid/<scene>/ (EXRs, compare.json, contact-sheet.png) and prints a markdown table of the
# efficiency ratios (python3 formats it). Usage: scripts/paper-grid.sh [SECONDS] [REF_SPP] [RES]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

seconds=${1:-4}
reference_spp=${2:-1024}
resolution=${3:-64x64}
for object in sphere bunny; do
  for light in directional cone env; do
    for surface in r0.2 r0.04 smooth; do
      scene="$object-$light-$surface"
      build/apps/snee compare "builtin:$scene" --time "$seconds" --reference-spp "$reference_spp" \
        --resolution "$resolution" -o "out/grid/$scene" -q >/dev/null
      echo "done $scene" >&2
    done
  done
done
python3 - <<'PY'
import json, pathlib
print("| scene | pt spp | snee spp | pt relMSE | snee relMSE | efficiency snee / pt | trimmed: pt | snee | ratio |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for d in sorted(pathlib.Path("out/grid").iterdir()):
    r = json.loads((d / "compare.json").read_text())
    pt, sn = r["integrators"][0], r["integrators"][1]
    ratio = f'{sn["efficiency_vs_first"]:.2f}' if pt["efficiency"] > 0 else "pt: no signal"
    print(f'| {r["scene"]} | {pt["spp"]} | {sn["spp"]} | {pt["relative_mse"]:.3g} | '
          f'{sn["relative_mse"]:.3g} | {ratio} | {pt["relative_mse_trimmed"]:.3g} | '
          f'{sn["relative_mse_trimmed"]:.3g} | {sn["efficiency_trimmed_vs_first"]:.2f} |')
PY
