#!/usr/bin/env python3
"""CPU time per pixel sample of snee renders, for comparing integrators and builds.

Renders every scene with every integrator and every given snee binary, REPEATS rounds with the
runs alternated inside each round (so other work on the machine slows all alike), and prints the
median of sampling_cpu_seconds / paths from `snee render --stats` (process CPU time of running
the work units, without scene setup) in nanoseconds, with two ratios: each integrator over the
first (e.g. snee / pt) within a build, and each build over the first (e.g. new / old) for an
integrator, as paths per CPU-second. docs/performance.md ("Issue 15's targets") was made with it:

  python3 scripts/cpu-per-sample.py --snee build/apps/snee --scenes sphere-cone-r0.04 \
      --integrators pt,snee --repeats 3
  python3 scripts/cpu-per-sample.py --snee /tmp/old/build/apps/snee --snee build/apps/snee \
      --scenes sphere-cone-r0.04,bunny-cone-r0.04 --integrators pt --repeats 5
"""
import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path


def render(snee, scene, integrator, args, out_dir):
    stats = Path(out_dir) / "stats.json"
    command = [snee, "render", f"builtin:{scene}", "--integrator", integrator, "--spp",
               str(args.spp), "--resolution", args.resolution, "--threads", str(args.threads),
               "--seed", "1", "-q", "-o", str(Path(out_dir) / "image.exr"), "--stats", str(stats)]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    s = json.loads(stats.read_text())
    simd = s.get("simd", {}).get("level", "sse4.2 (no dispatch)")
    return s["sampling_cpu_seconds"] / s["paths"] * 1e9, simd


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--snee", action="append", required=True, help="a snee binary (repeatable)")
    p.add_argument("--scenes", required=True, help="comma-separated built-in scene names")
    p.add_argument("--integrators", default="pt,snee")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--resolution", default="128x128")
    p.add_argument("--threads", type=int, default=1)
    args = p.parse_args()
    scenes = args.scenes.split(",")
    integrators = args.integrators.split(",")
    ns = {}  # (build, scene, integrator) -> [ns per path]
    simd = {}
    with tempfile.TemporaryDirectory() as out_dir:
        for r in range(args.repeats):
            for scene in scenes:
                for integrator in integrators:
                    for b, snee in enumerate(args.snee):
                        t, level = render(snee, scene, integrator, args, out_dir)
                        ns.setdefault((b, scene, integrator), []).append(t)
                        simd[b] = level
            print(f"round {r + 1} of {args.repeats} done", file=sys.stderr)
    med = {k: statistics.median(v) for k, v in ns.items()}
    for b, snee in enumerate(args.snee):
        print(f"build {b}: {snee} (SIMD {simd[b]})")
    header = ["scene", "integrator"] + [f"ns/path build {b}" for b in range(len(args.snee))]
    header += [f"{i} / {integrators[0]} build {b}" for b in range(len(args.snee))
               for i in integrators[1:]]
    header += [f"build {b} / build 0 (paths per CPU-s)" for b in range(1, len(args.snee))]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for scene in scenes:
        for integrator in integrators:
            row = [scene, integrator]
            row += [f"{med[(b, scene, integrator)]:.0f}" for b in range(len(args.snee))]
            row += [f"{med[(b, scene, i)] / med[(b, scene, integrators[0])]:.2f}"
                    if integrator == integrators[0] else ""
                    for b in range(len(args.snee)) for i in integrators[1:]]
            row += [f"{med[(0, scene, integrator)] / med[(b, scene, integrator)]:.2f}"
                    for b in range(1, len(args.snee))]
            print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
