#!/usr/bin/env bash
# Runs every libFuzzer target of a PGMCL_FUZZ build for a bounded time.
#   tests/fuzz/run_all.sh BUILD_DIR SECONDS
# Each target fuzz_<name> starts from a fresh copy of tests/fuzz/corpus/<name>/ (the grown
# corpus and any crash input are kept under BUILD_DIR/fuzz-runs/<name>/). Failures: a crash,
# an ASan/UBSan report, a hang (-timeout=5 s per input) or OOM (-rss_limit_mb=2048).
# Runs PGMCL_FUZZ_JOBS targets at once (default 2, one per core). Prints the executions per
# target; exits non-zero if any target failed.
# PGMCL_FUZZ_TARGETS="carmen tum" limits the run to those targets.
set -uo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 BUILD_DIR SECONDS" >&2
  exit 2
fi
build=$(cd "$1" && pwd) || exit 2
seconds=$2
here=$(cd "$(dirname "$0")" && pwd)

mapfile -t bins < <(find "$build" -type f -name 'fuzz_*' -perm -u+x ! -name '*.*' | sort)
if [ ${#bins[@]} -eq 0 ]; then
  echo "run_all.sh: no fuzz_* binaries under $build (build target pgmcl_fuzzers)" >&2
  exit 2
fi

# One target per core (PGMCL_FUZZ_JOBS, default 2): each libFuzzer process is single-threaded.
jobs=${PGMCL_FUZZ_JOBS:-2}

run_target() {  # bin -> writes $run/rc; never fails itself
  local bin=$1 name seeds run dict=()
  name=$(basename "$bin")
  name=${name#fuzz_}
  seeds=$here/corpus/$name
  run=$build/fuzz-runs/$name
  rm -rf "$run"
  mkdir -p "$run/corpus" "$run/artifacts"
  if [ ! -d "$seeds" ]; then
    echo "run_all.sh: no seed corpus $seeds for fuzz_$name" >"$run/log.txt"
    echo 2 >"$run/rc"
    return
  fi
  cp -r "$seeds/." "$run/corpus/"
  [ -f "$here/dict/$name.dict" ] && dict=("-dict=$here/dict/$name.dict")
  "$bin" "$run/corpus" "${dict[@]}" -max_total_time="$seconds" -timeout=5 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$run/artifacts/" \
    >"$run/log.txt" 2>&1
  echo $? >"$run/rc"
}

selected=()
for bin in "${bins[@]}"; do
  name=$(basename "$bin")
  name=${name#fuzz_}
  if [ -n "${PGMCL_FUZZ_TARGETS:-}" ] && [[ " $PGMCL_FUZZ_TARGETS " != *" $name "* ]]; then
    continue
  fi
  selected+=("$bin")
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  run_target "$bin" &
done
wait

failed=0
printf '%-12s %12s %8s  %s\n' target executions result log
for bin in "${selected[@]}"; do
  name=$(basename "$bin")
  name=${name#fuzz_}
  run=$build/fuzz-runs/$name
  rc=$(cat "$run/rc" 2>/dev/null || echo 2)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$run/log.txt" | tail -n 1)
  result=ok
  if [ "$rc" -ne 0 ]; then
    result="FAIL($rc)"
    failed=1
  fi
  printf '%-12s %12s %8s  %s\n' "$name" "${execs:-?}" "$result" "$run/log.txt"
  if [ "$rc" -ne 0 ]; then
    grep -m 1 -E 'ERROR: (libFuzzer|AddressSanitizer)|runtime error|invariant violated' \
      "$run/log.txt" >&2 || tail -n 20 "$run/log.txt" >&2
    ls "$run/artifacts" >&2
  fi
done
exit $failed
