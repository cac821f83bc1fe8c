#!/usr/bin/env bash
# What `--noise-target` saves at equal error (docs/budgets.md, "What the noise target saves"):
# for the 18 paper-grid scenes and builtin:default, renders a long uniform reference, an
# adaptive render and two uniform renders at about the adaptive render's mean spp (independent
# seeds), and measures each with `snee error`. A uniform render's relative MSE falls as 1/spp,
# so the uniform spp with the adaptive render's error is n* = n0 x relMSE(uniform n0) /
# relMSE(adaptive), and the saving is n* / mean adaptive spp. The scenes in VERIFY are also
# rendered uniformly at n*, whose error should then match the adaptive one within the spread of
# the two uniform seeds. Every render uses snee and tiles of TILE pixels. Writes
# out/noise-savings/<scene>/ (EXRs and `snee error` JSON) and prints a markdown table.
# Usage: scripts/noise-target-savings.sh [TARGET] [MAX_SPP] [REF_SPP] [RES] [DEFAULT_RES]
#   [DEFAULT_REF_SPP] (grid defaults 0.1, 256, 4096, 48x48; builtin:default keeps its own
#   target 0.05 and 256 spp, at 120x90 against 2048 spp). SNEE_SAVINGS_SCENES="NAME ..." runs
#   only those scenes.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

target=${1:-0.1}
max_spp=${2:-256}
reference_spp=${3:-4096}
resolution=${4:-48x48}
default_resolution=${5:-120x90}
default_reference_spp=${6:-2048}
tile=8
verify=" bunny-env-smooth default "
snee=build/apps/snee
root=out/noise-savings

# relative_mse (or another top-level figure) of a `snee error --json` file.
figure() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])' "$@"; }

# measure DIR NAME: `snee error` of DIR/NAME.exr against DIR/reference.exr into DIR/NAME.json.
measure() { "$snee" error "$1/$2.exr" "$1/reference.exr" --json "$1/$2.json" >/dev/null; }

# render ARGS...: `snee render ARGS`; if it fails, a table row saying so (run's scene and dir)
# instead of the scene's figures, and status 1, so the other scenes still run.
render() {
  local status=0
  "$snee" "${common[@]}" "$@" >/dev/null 2>"$dir/stderr.txt" || status=$?
  if [[ $status -ne 0 ]]; then
    echo "| $scene | snee render ${*} failed with exit code $status ($dir/stderr.txt) |"
    return 1
  fi
}

# run SCENE RES REF_SPP TARGET MAX_SPP: one table row.
run() {
  local scene=$1 res=$2 ref_spp=$3 scene_target=$4 scene_max=$5 dir="$root/$1"
  local common=(render "builtin:$scene" --integrator snee --resolution "$res" --tile-size "$tile" -q)
  mkdir -p "$dir"
  render --noise-target 0 --spp "$ref_spp" --seed 1000003 -o "$dir/reference.exr" || return 0
  render --noise-target "$scene_target" --spp "$scene_max" --seed 1 -o "$dir/adaptive.exr" || return 0
  measure "$dir" adaptive
  local mean_spp n0
  mean_spp=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["render"]["spp"]["mean"])' \
    "$dir/adaptive.json")
  n0=$(python3 -c 'import sys; print(max(16, round(float(sys.argv[1]))))' "$mean_spp")
  for seed in 2 3; do
    render --noise-target 0 --spp "$n0" --seed "$seed" -o "$dir/uniform-$seed.exr" || return 0
    measure "$dir" "uniform-$seed"
  done
  # Each figure of the adaptive render, then of both uniform ones: full and trimmed relMSE.
  local figures=() name
  for name in adaptive uniform-2 uniform-3; do
    figures+=("$(figure "$dir/$name.json" relative_mse)" "$(figure "$dir/$name.json" relative_mse_trimmed)")
  done
  local n_star verified=""
  n_star=$(python3 -c 'import sys; n0, a, _, b, _, c, _ = map(float, sys.argv[1:]); print(round(n0 * (b + c) / 2 / a))' \
    "$n0" "${figures[@]}")
  if [[ $verify == *" $scene "* ]]; then
    render --noise-target 0 --spp "$n_star" --seed 4 -o "$dir/equal.exr" || return 0
    measure "$dir" equal
    verified=$(figure "$dir/equal.json" relative_mse)
  fi
  python3 - "$scene" "$mean_spp" "$n0" "$verified" "$(figure "$dir/adaptive.json" reference_noise)" \
    "${figures[@]}" <<'EOF'
import sys
scene, mean_spp, n0, verified, noise = sys.argv[1:6]
a, a_t, u2, u2_t, u3, u3_t = map(float, sys.argv[6:])
mean_spp, n0, noise = float(mean_spp), int(n0), float(noise)
n_star = round(n0 * (u2 + u3) / 2 / a)
n_star_t = round(n0 * (u2_t + u3_t) / 2 / a_t)
spread = abs(u2 - u3) / ((u2 + u3) / 2)
check = f"{float(verified):.2e} ({float(verified) / a:.2f}x)" if verified else ""
print(f"| {scene} | {mean_spp:.1f} | {a:.2e} ({a_t:.2e}) | {n0} | {u2:.2e}, {u3:.2e} ({spread:.0%}) "
      f"| {n_star} | **{n_star / mean_spp:.2f}** | {n_star_t} | {n_star_t / mean_spp:.2f} "
      f"| {noise:.1e} | {check} |", flush=True)
EOF
}

echo "| scene | adaptive mean spp | adaptive relMSE (trimmed) | uniform n0 | uniform n0 relMSE, seeds 2, 3 (spread) | equal-error uniform spp n* | saving n*/mean | n* from trimmed | saving, trimmed | reference noise | uniform at n*: relMSE (/ adaptive) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
source scripts/grid-scenes.sh
scenes=("${grid_scenes[@]}" default)
# SNEE_SAVINGS_SCENES="a b": only those rows (to redo one scene).
[[ -n ${SNEE_SAVINGS_SCENES:-} ]] && read -r -a scenes <<<"$SNEE_SAVINGS_SCENES"
for scene in "${scenes[@]}"; do
  if [[ $scene == default ]]; then
    run default "$default_resolution" "$default_reference_spp" 0.05 256
  else
    run "$scene" "$resolution" "$reference_spp" "$target" "$max_spp"
  fi
done
