#!/usr/bin/env bash
# All micro-benchmarks, under OMP_NUM_THREADS=1 and 2, one command:
#
#   bench/run_micro.sh [--out DIR] [--build DIR] [--threads "1 2"] [--quick] [-- <benchmark flags>]
#
# --out    results (default: <repo>/results/bench/micro): per binary and thread count a
#          console log <bench>_t<T>.txt and CSV(s) (measurement_t<T>.csv, scaling_t<T>.csv,
#          table_build_t<T>.csv, filter_step_t<T>.csv, primitives_t<T>.csv)
# --build  CMake build dir (default: <repo>/build-bench; configured and built if needed)
# --quick  smoke test: --benchmark_min_time=0.05 and smaller grids (a loaded machine's
#          figures are not results; run without --quick on a quiet machine)
# Anything after `--` is passed to every benchmark binary (e.g. --benchmark_repetitions=3).
# Full run: roughly 15-25 min on a quiet 2-core machine (the 200 m tables dominate setup).
set -euo pipefail

source "$(dirname "$0")/common.sh"
out="$root/results/bench/micro"
thread_list="1 2"
quick=0
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --threads) thread_list=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    --) shift; extra=("$@"); break ;;
    *) bench_option "$@"; shift "$bench_shift" ;;
  esac
done

targets=(measurement_bench table_build_bench primitives_bench filter_step_bench)
bench_build "${targets[@]}"
mkdir -p "$out"

declare -A args
if [[ $quick -eq 1 ]]; then
  mt=(--benchmark_min_time=0.05)
  args[measurement_bench]="--sizes=10,50 --particles=1000,5000 --beams=60,270"
  args[table_build_bench]="--sizes=10x10,50x50,200x200"
  args[primitives_bench]=""
  args[filter_step_bench]="--particles=1000,5000 --beams=60,1081"
else
  mt=()
  args[measurement_bench]=""
  args[table_build_bench]=""
  args[primitives_bench]=""
  args[filter_step_bench]=""
fi

{
  echo "host: $(uname -n), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "date: $(date -u +%FT%TZ)"
} >"$out/machine.txt"

for t in $thread_list; do
  for b in "${targets[@]}"; do
    echo "== $b, OMP_NUM_THREADS=$t"
    # shellcheck disable=SC2086
    OMP_NUM_THREADS=$t "$build/bench/$b" --out="$out" ${args[$b]} "${mt[@]}" "${extra[@]}" \
      2>&1 | tee "$out/${b}_t$t.txt"
  done
done
echo "run_micro: wrote $out (load at the end: $(cut -d' ' -f1-3 /proc/loadavg))"
