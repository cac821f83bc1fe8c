#!/usr/bin/env python3
"""Predicted efficiency of snee-mpi on 1 to 1024 ranks, static against dynamic split
(docs/performance.md, "Several processes"), from measured per-tile costs.

Input: the --stats JSON of `snee render --stats-tiles` (tile_seconds: each tile's stage seconds
summed over threads, raster order). Each rank is modelled as THREADS threads that share a tile
perfectly (a tile is spp / samples-per-unit units, spread over the rank's threads), so a tile
takes cost x SCALE / THREADS on a rank; SCALE turns the measured spp into the one modelled.

static:  rank r renders the tiles whose raster index is r modulo the ranks (--split static).
dynamic: a rank that is done with a tile claims the next one in raster order
         (--split dynamic): one round trip of LATENCY, during which it renders nothing (in
         snee the other threads go on with the tile's units, so this overstates the cost),
         plus queueing at rank 0's counter, which serves one atomic at a time in SERVICE.

The last line is a what-if that snee does not do: dynamic claims in decreasing cost order.
Efficiency = sum of tile times / (ranks x the slowest rank's finish). Prints a markdown table;
with --svg, writes the plot (drawn by hand: python3's standard library only).
"""
import argparse
import heapq
import json
import math


def static_finish(costs, ranks):
    loads = [0.0] * ranks
    for i, c in enumerate(costs):
        loads[i % ranks] += c
    return max(loads)


def dynamic_finish(costs, ranks, latency, service):
    # (time the rank asks for a tile, rank); the counter serves claims in arrival order.
    asking = [(0.0, r) for r in range(ranks)]
    heapq.heapify(asking)
    counter_free = 0.0
    finish = 0.0
    for c in costs:
        t, r = heapq.heappop(asking)
        served = max(t + latency / 2, counter_free)
        counter_free = served + service
        done = served + latency / 2 + c
        finish = max(finish, done)
        heapq.heappush(asking, (done, r))
    # Each rank's last claim finds the counter past the end: one more round trip.
    return max(finish, max(t for t, _ in asking) + latency)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stats", help="snee render --stats FILE --stats-tiles output")
    ap.add_argument("--scale", type=float, default=1.0,
                    help="multiply every tile's cost (modelled spp / measured spp)")
    ap.add_argument("--threads", type=int, default=16, help="threads per rank")
    ap.add_argument("--latency-us", type=float, action="append", required=True,
                    help="claim round trip, microseconds (repeat for several dynamic lines)")
    ap.add_argument("--service-us", type=float, default=0.1,
                    help="time rank 0's counter is busy per claim, microseconds")
    ap.add_argument("--max-ranks", type=int, default=1024)
    ap.add_argument("--svg", help="write the plot here")
    ap.add_argument("--title", default="predicted efficiency of snee-mpi")
    a = ap.parse_args()

    stats = json.load(open(a.stats))
    costs = [c * a.scale / a.threads for c in stats["tile_seconds"]]
    total = sum(costs)
    ranks = [1 << k for k in range(int(math.log2(a.max_ranks)) + 1)]
    lines = {"static": [total / (n * static_finish(costs, n)) for n in ranks]}
    for lat in a.latency_us:
        lines[f"dynamic, {lat:g} us claim"] = [
            total / (n * dynamic_finish(costs, n, lat * 1e-6, a.service_us * 1e-6))
            for n in ranks]
    # What-if, not implemented: claims in decreasing cost (needs the costs before rendering).
    lines[f"what-if: costliest first, {a.latency_us[-1]:g} us"] = [
        total / (n * dynamic_finish(sorted(costs, reverse=True), n, a.latency_us[-1] * 1e-6,
                                    a.service_us * 1e-6)) for n in ranks]
    # No split can beat the costliest tile: the bound a finer tile grid would lift.
    bound = [min(1.0, total / (n * max(costs))) for n in ranks]

    print(f"{len(costs)} tiles, {total:.1f} s on one rank of {a.threads} threads, "
          f"costliest tile {max(costs) * 1e3:.1f} ms, mean {total / len(costs) * 1e3:.2f} ms")
    names = list(lines)
    print("| ranks | " + " | ".join(names) + " | bound (costliest tile) |")
    print("| ---: |" + " ---: |" * (len(names) + 1))
    for i, n in enumerate(ranks):
        print(f"| {n} | " + " | ".join(f"{100 * lines[k][i]:.1f}%" for k in names) +
              f" | {100 * bound[i]:.1f}% |")
    if a.svg:
        lines["bound: costliest tile"] = bound
        open(a.svg, "w").write(svg(ranks, lines, a.title,
                                   f"{len(costs)} measured tile costs x {a.scale:g}, "
                                   f"{a.threads} threads per rank"))


def svg(ranks, lines, title, subtitle):
    w, h, left, right, top, bottom = 780, 420, 70, 290, 60, 50
    pw, ph = w - left - right, h - top - bottom
    x = lambda n: left + pw * math.log2(n) / math.log2(ranks[-1])
    y = lambda e: top + ph * (1 - e)
    colours = ["#c0392b", "#2471a3", "#229954", "#7d3c98", "#888888"]
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{left}" y="24" font-size="15" font-weight="bold">{title}</text>',
           f'<text x="{left}" y="42" fill="#555">{subtitle}</text>']
    for e in [0, 0.25, 0.5, 0.75, 1.0]:
        out.append(f'<line x1="{left}" y1="{y(e):.1f}" x2="{left + pw}" y2="{y(e):.1f}" '
                   f'stroke="#ddd"/>')
        out.append(f'<text x="{left - 8}" y="{y(e) + 4:.1f}" text-anchor="end">'
                   f'{int(100 * e)}%</text>')
    for n in ranks:
        out.append(f'<text x="{x(n):.1f}" y="{top + ph + 18}" text-anchor="middle">{n}</text>')
    out.append(f'<text x="{left + pw / 2}" y="{h - 10}" text-anchor="middle">ranks</text>')
    out.append(f'<text x="18" y="{top + ph / 2}" transform="rotate(-90 18 {top + ph / 2})" '
               f'text-anchor="middle">parallel efficiency</text>')
    out.append(f'<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" '
               f'stroke="#333"/>')
    for i, (name, values) in enumerate(lines.items()):
        c = colours[i % len(colours)]
        dash = ' stroke-dasharray="5,4"' if name.startswith("bound") else ""
        pts = " ".join(f"{x(n):.1f},{y(v):.1f}" for n, v in zip(ranks, values))
        out.append(f'<polyline points="{pts}" fill="none" stroke="{c}" stroke-width="2"{dash}/>')
        for n, v in zip(ranks, values):
            out.append(f'<circle cx="{x(n):.1f}" cy="{y(v):.1f}" r="3" fill="{c}"/>')
        ly = top + 14 + 20 * i
        out.append(f'<line x1="{left + pw + 14}" y1="{ly - 4}" x2="{left + pw + 38}" '
                   f'y2="{ly - 4}" stroke="{c}" stroke-width="2"{dash}/>')
        out.append(f'<text x="{left + pw + 44}" y="{ly}">{name}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    main()
