#!/usr/bin/env bash
# The several-process study of docs/performance.md ("Several processes"): renders one scene
# with snee-mpi on 1 to 4 ranks of one thread each, with --split static and --split dynamic,
# then the uneven cases: 2 ranks where one has 2 threads and the other 1, and 3 ranks on tiles
# of 32 pixels (16 tiles, the object's cost concentrated in a few of them). Every image is
# checked bitwise against `snee render` (pixel SHA-1 by `iinfo`, openimageio-tools). Prints a
# markdown table: the slowest rank's sampling seconds (the job's), each rank's tiles, busy and
# join-wait seconds, and the imbalance (largest busy / mean busy). Writes out/mpi-scale/.
# Usage: scripts/mpi-scale.sh [REPEATS] (default 3; the row is the repeat with the median
# job seconds).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

repeats=${1:-3}
root=out/mpi-scale
mpi=(mpirun --oversubscribe)
[ "$(id -u)" = 0 ] && mpi+=(--allow-run-as-root)
scene=(builtin:bunny-cone-r0.04 --integrator snee --resolution 128x128 --spp 64 --quiet)
rm -rf "$root"
mkdir -p "$root"

hash_of() { iinfo --hash "$1" | sed -n 's/.*SHA-1: //p'; }

# run NAME SPLIT TILE THREADS...: one snee-mpi job per repeat, one rank per THREADS entry.
run() {
  local name=$1 split=$2 tile=$3
  shift 3
  [ -f "$root/one-$tile.exr" ] ||
    build/apps/snee render "${scene[@]}" --tile-size "$tile" --threads 2 -o "$root/one-$tile.exr" \
      >/dev/null
  for ((i = 0; i < repeats; ++i)); do
    local command=("${mpi[@]}") first=1
    for t in "$@"; do
      [ $first = 1 ] || command+=(:)
      first=0
      command+=(-np 1 build/apps/mpi/snee-mpi render "${scene[@]}" --tile-size "$tile"
        --split "$split" --threads "$t" -o "$root/$name-$i.exr" --stats "$root/$name-$i.json")
    done
    "${command[@]}" >/dev/null
    if [ "$(hash_of "$root/$name-$i.exr")" != "$(hash_of "$root/one-$tile.exr")" ]; then
      echo "error: $name-$i.exr is not the single-process image" >&2
      exit 1
    fi
  done
  python3 - "$name" "$split" "$root" "$repeats" "$tile" "$@" <<'PY'
import json, statistics, sys
name, split, root, repeats, tile = sys.argv[1:6]
threads = sys.argv[6:]
runs = [json.load(open(f"{root}/{name}-{i}.json")) for i in range(int(repeats))]
runs.sort(key=lambda r: r["sampling_seconds"])
r = runs[len(runs) // 2]
p = r["processes"]
busy = [x["busy_seconds"] for x in p]
cell = lambda key, fmt: " / ".join(fmt % x[key] for x in p)
size = "" if tile == "16" else f", {tile} px"
print(f"| {len(p)} x {'+'.join(threads)}{size} | {split} | {r['sampling_seconds']:.2f} "
      f"({', '.join('%.2f' % x['sampling_seconds'] for x in runs)}) | {cell('tiles', '%d')} | "
      f"{cell('busy_seconds', '%.2f')} | {cell('join_seconds', '%.2f')} | "
      f"{max(busy) / statistics.mean(busy):.2f} |")
PY
}

echo "| ranks x threads | split | job seconds (repeats) | tiles per rank | busy s per rank | join wait s per rank | imbalance |"
echo "| --- | --- | ---: | --- | --- | --- | ---: |"
for split in static dynamic; do
  run "r1-$split" "$split" 16 1
  run "r2-$split" "$split" 16 1 1
  run "r3-$split" "$split" 16 1 1 1
  run "r4-$split" "$split" 16 1 1 1 1
  run "uneven-$split" "$split" 16 2 1
  run "coarse-$split" "$split" 32 1 1 1
done
