#!/usr/bin/env python3
"""Markdown tables of docs/performance.md from `snee bench --json` files.

Usage: scripts/bench-tables.py FULL.json [REPEAT.json ...]

FULL.json (a run of every workload) gives the throughput, traversal and stage tables; the
target table takes, per workload and thread count, the median (and range) of the
wavefront / megakernel ratio over every file that has the workload, so repeated runs of
`snee bench --only ...` narrow it.
"""
import json
import statistics
import sys

STAGES = ["generate", "extend", "medium_event", "snee_probe", "subdivision", "shade_surface",
          "shade_escaped", "shadow_connect", "retire"]
KINDS = ["camera", "extension", "shadow", "probe"]


def runs_by(workload):
    return {(r["schedule"], r["threads"]): r for r in workload["runs"]}


def throughput(bench):
    print("| workload | threads | megakernel | local | global | local ÷ mega, wall | "
          "local ÷ mega, CPU | global ÷ mega, CPU | CPU share (mega, local, global) | "
          "SIMD lanes used, local |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for w in bench["workloads"]:
        runs = runs_by(w)
        for t in bench["settings"]["threads"]:
            m, l, g = (runs[(s, t)] for s in ("megakernel", "local", "global"))
            share = ", ".join(f'{100 * r["cpu_share"]:.0f}%' for r in (m, l, g))
            print(f'| {w["name"]} | {t} | {m["paths_per_second"] / 1e3:,.0f}k | '
                  f'{l["paths_per_second"] / 1e3:,.0f}k | {g["paths_per_second"] / 1e3:,.0f}k | '
                  f'{l["vs_megakernel"]["paths_per_second"]:.2f} | '
                  f'**{l["vs_megakernel"]["paths_per_cpu_second"]:.2f}** | '
                  f'{g["vs_megakernel"]["paths_per_cpu_second"]:.2f} | {share} | '
                  f'{100 * l["simd"]["lane_occupancy"]:.1f}% |')


def traversal(bench):
    print("| workload | triangles | rays per path: camera, extension, shadow, probe | "
          "raw Embree Mrays/CPU-s: closest 1x / 1M, occlusion 1x / 1M, camera 1x / 1M | "
          "renderer Mrays/CPU-s: mega, local | local ÷ raw closest 1x | "
          "traversal-bound share: mega, local | queue occupancy | extend batch | "
          "peak RSS MiB: mega, local, global |")
    print("|---|---:|---|---|---|---:|---|---:|---:|---|")
    for w in bench["workloads"]:
        runs = runs_by(w)
        m, l, g = (runs[(s, 1)] for s in ("megakernel", "local", "global"))
        q = w["raw_embree"]["queries"]
        rate = lambda k: q[k]["mrays_per_cpu_second"]
        per_path = ", ".join(f'{l["rays"][k] / l["paths"]:.2f}' for k in KINDS)
        raw = (f'{rate("closest_single"):.2f} / {rate("closest_stream"):.2f}, '
               f'{rate("occlusion_single"):.2f} / {rate("occlusion_stream"):.2f}, '
               f'{rate("camera_single"):.1f} / {rate("camera_stream"):.1f}')
        bound = lambda r: f'{100 * r["ratio_to_raw_embree"]["traversal_bound_fraction"]:.0f}%'
        rss = ", ".join(f'{r["peak_memory_mib"]:.0f}' for r in (m, l, g))
        print(f'| {w["name"]} | {w["triangles"]:,} | {per_path} | {raw} | '
              f'{m["mrays_per_cpu_second"]["total"]:.2f}, {l["mrays_per_cpu_second"]["total"]:.2f} | '
              f'{100 * l["ratio_to_raw_embree"]["total_vs_closest_single"]:.0f}% | '
              f'{bound(m)}, {bound(l)} | {l["queue_occupancy"]:.3f} | '
              f'{l["mean_extend_batch"]:.0f} | {rss} |')


def stages(bench):
    print("| workload | schedule | " + " | ".join(s.replace("_", " ") for s in STAGES) +
          " | unattributed | CPU total |")
    print("|---|---|" + "---:|" * (len(STAGES) + 2))
    for w in bench["workloads"]:
        runs = runs_by(w)
        for schedule in ("megakernel", "local"):
            r = runs[(schedule, 1)]
            ns = lambda seconds: 1e9 * seconds / r["paths"]
            cells = [ns(r["stages"][s]["seconds"]) for s in STAGES]
            total = ns(r["cpu_seconds"])
            print(f'| {w["name"]} | {schedule} | ' + " | ".join(f"{c:.0f}" for c in cells) +
                  f' | {total - sum(cells):.0f} | {total:.0f} |')


def targets(files):
    ratios = {}
    for bench in files:
        for w in bench["workloads"]:
            for r in w["runs"]:
                if r["schedule"] == "local":
                    key = (w["name"], r["threads"])
                    ratios.setdefault(key, []).append(r["vs_megakernel"]["paths_per_cpu_second"])
    print("| workload | threads | local ÷ megakernel, paths per CPU-second: median (range) | runs |")
    print("|---|---:|---:|---:|")
    for (name, t), values in ratios.items():
        print(f"| {name} | {t} | {statistics.median(values):.2f} "
              f"({min(values):.2f}-{max(values):.2f}) | {len(values)} |")


def main():
    files = [json.load(open(path)) for path in sys.argv[1:]]
    if not files:
        sys.exit(__doc__)
    full = files[0]
    for title, table in (("Throughput", throughput), ("Traversal", traversal),
                         ("Stages, ns per path, 1 thread", stages)):
        print(f"\n### {title}\n")
        table(full)
    print("\n### Targets\n")
    targets(files)


if __name__ == "__main__":
    main()
