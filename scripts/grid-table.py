#!/usr/bin/env python3
"""Markdown table of docs/results.md from the compare.json files paper-grid.sh writes.

Usage: scripts/grid-table.py [GRID_DIR]   (default out/grid: GRID_DIR/<scene>/run<N>/compare.json)

Per scene, medians over the runs (range in brackets for the efficiency ratios): spp reached,
relMSE, snee's efficiency over pt's (full and with the 0.1% worst pixels trimmed), and the
two factors of that ratio: snee's time per sample over pt's, and the error reduction per
sample, (relMSE x spp) of pt over snee's.
"""
import json
import pathlib
import statistics
import sys


def main():
    grid = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out/grid")
    med = statistics.median
    print("| scene | spp pt / snee | relMSE pt | relMSE snee | efficiency snee / pt | "
          "trimmed relMSE pt | snee | efficiency ratio (trimmed) | time per sample snee / pt | "
          "error per sample pt / snee |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for d in sorted(p for p in grid.iterdir() if p.is_dir()):
        runs = [json.loads(p.read_text()) for p in sorted(d.glob("run*/compare.json"))]
        if not runs:
            continue
        pt = [r["integrators"][0] for r in runs]
        sn = [r["integrators"][1] for r in runs]
        ratios = [s["efficiency_vs_first"] for s in sn]
        trimmed = [s["efficiency_trimmed_vs_first"] for s in sn]
        cost = [(s["seconds"] / s["spp"]) / (p["seconds"] / p["spp"]) for p, s in zip(pt, sn)]
        per_sample = [(p["relative_mse"] * p["spp"]) / (s["relative_mse"] * s["spp"])
                      for p, s in zip(pt, sn)]
        print(f'| {d.name} | {med([p["spp"] for p in pt]):.0f} / {med([s["spp"] for s in sn]):.0f} | '
              f'{med([p["relative_mse"] for p in pt]):.3g} | '
              f'{med([s["relative_mse"] for s in sn]):.3g} | {med(ratios):.2f} '
              f'({min(ratios):.2f}-{max(ratios):.2f}) | '
              f'{med([p["relative_mse_trimmed"] for p in pt]):.3g} | '
              f'{med([s["relative_mse_trimmed"] for s in sn]):.3g} | {med(trimmed):.2f} '
              f'({min(trimmed):.2f}-{max(trimmed):.2f}) | {med(cost):.2f} | {med(per_sample):.2f} |')


if __name__ == "__main__":
    main()
