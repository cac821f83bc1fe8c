#!/usr/bin/env bash
# Builds the libFuzzer harnesses of tests/fuzz/ with clang in build-fuzz/ and runs each for a
# bounded time, starting from its committed corpus (tests/fuzz/corpus/<loader>/: valid seeds
# and the reproducers of past findings, so those are replayed first). Exits 1 if any fuzzer
# left a crash, leak, timeout or out-of-memory artefact; they are kept in the output directory.
#
#   bash scripts/fuzz.sh [SECONDS_PER_FUZZER (default 60)] [FUZZER ...]
#   bash scripts/fuzz.sh --runs FUZZER=RUNS [FUZZER=RUNS ...]
#
# FUZZER is scene_json, obj, ply or env_image (default: all four, as many at a time as there
# are cores, one core each). The first form explores for a time, from a random seed: new
# findings come from it. The second replays the corpus and then makes exactly RUNS mutations
# from seed 1, the same inputs on every machine, so that CI (.ci/run) fails only on what a run
# here would have found too.
# Output goes to $SNEE_FUZZ_OUT (default out/fuzz/): <loader>/corpus holds the inputs this run
# found interesting, <loader>/ its artefacts and <loader>/log the fuzzer's output.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

fuzzers=()
declare -A limit
if [[ ${1:-} == --runs ]]; then
  shift
  (($# > 0)) || { echo "error: --runs needs FUZZER=RUNS arguments" >&2; exit 2; }
  for spec in "$@"; do
    if [[ ! $spec =~ ^(scene_json|obj|ply|env_image)=([1-9][0-9]*)$ ]]; then
      echo "error: '$spec' is not FUZZER=RUNS (FUZZER: scene_json, obj, ply or env_image)" >&2
      exit 2
    fi
    fuzzers+=("${BASH_REMATCH[1]}")
    limit[${BASH_REMATCH[1]}]="-runs=${BASH_REMATCH[2]} -seed=1"
  done
  what="a fixed number of runs each, seed 1"
else
  seconds=${1:-60}
  shift || true
  fuzzers=("$@")
  ((${#fuzzers[@]} > 0)) || fuzzers=(scene_json obj ply env_image)
  for name in "${fuzzers[@]}"; do limit[$name]="-max_total_time=$seconds"; done
  what="${seconds}s each"
fi
out=${SNEE_FUZZ_OUT:-out/fuzz}

for tool in clang clang++; do
  if ! command -v "$tool" >/dev/null; then
    echo "error: $tool not found (bash scripts/setup.sh installs it)" >&2
    exit 1
  fi
done
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DSNEE_FUZZ=ON \
  -DSNEE_BUILD_TESTS=OFF -DSNEE_BUILD_BENCHMARKS=OFF -DSNEE_MPI=OFF "${launcher[@]}" \
  --log-level=WARNING >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target "${fuzzers[@]/#/fuzz_}"

# Each run writes its inputs to a tmpfs directory of its own (tests/fuzz/input_file.h), removed
# here even when a crash left it behind.
scratch_root=/dev/shm
[[ -d $scratch_root && -w $scratch_root ]] || scratch_root=${TMPDIR:-/tmp}
scratch=$(mktemp -d "$scratch_root/snee-fuzz.XXXXXX")
trap 'rm -rf "$scratch"' EXIT

# Leaks are findings (a leak report ends the run), except the library bugs
# tests/sanitizer/lsan.supp lists with their reasons. Undefined behaviour aborts already
# (-fno-sanitize-recover); the stack makes the report usable.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}

# One fuzzer per core at a time: each is single-threaded, and with fixed runs and seeds the
# inputs do not depend on what runs beside it.
fuzz_one() {
  local name=$1 dir=$out/$1 bound options dict status=0
  read -ra bound <<<"${limit[$name]}"
  options=("${bound[@]}" -timeout=10 -rss_limit_mb=2048
           -print_final_stats=1 -artifact_prefix="$dir/")
  dict=tests/fuzz/$name.dict
  [[ -f $dict ]] && options+=(-dict="$dict")
  TMPDIR=$scratch build-fuzz/tests/fuzz/fuzz_"$name" "${options[@]}" "$dir/corpus" \
    "tests/fuzz/corpus/$name" >"$dir/log" 2>&1 || status=$?
  echo "$status" >"$dir/status"
}

for name in "${fuzzers[@]}"; do
  rm -rf "${out:?}/$name"
  mkdir -p "$out/$name/corpus"
  echo "fuzz_$name: ${limit[$name]}, artefacts in $out/$name/" >&2
  while (($(jobs -rp | wc -l) >= $(nproc))); do wait -n || true; done
  fuzz_one "$name" &
done
wait

failed=()
for name in "${fuzzers[@]}"; do
  dir=$out/$name
  status=$(cat "$dir/status" 2>/dev/null || echo "no status")
  echo "fuzz_$name:" >&2
  grep -E '^(Done [0-9]+ runs|stat::peak_rss_mb)' "$dir/log" >&2 || true
  shopt -s nullglob
  artefacts=("$dir"/crash-* "$dir"/leak-* "$dir"/timeout-* "$dir"/oom-*)
  shopt -u nullglob
  if [[ $status != 0 ]] || ((${#artefacts[@]} > 0)); then
    failed+=("$name")
    echo "fuzz_$name FAILED (exit $status): ${artefacts[*]:-no artefact, see $dir/log}" >&2
    first_report='^==[0-9]+== ?ERROR|runtime error|^terminate called'
    grep -m1 -A12 -E "$first_report" "$dir/log" >&2 || tail -20 "$dir/log" >&2
  fi
done

if ((${#failed[@]} > 0)); then
  echo "fuzzing found problems in: ${failed[*]}; reproduce with" \
    "build-fuzz/tests/fuzz/fuzz_NAME ARTEFACT (tests/fuzz/README.md)" >&2
  exit 1
fi
echo "fuzzing: no findings in ${fuzzers[*]} ($what)" >&2
