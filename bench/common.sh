# Sourced by bench/run_micro.sh, sweep.sh and mrpt_side_by_side.sh (not run on its own):
# the repository paths and defaults, the options every script takes, the build step and
# the dataset filter. The sourcing script then sets its own defaults and parses
#
#   while [[ $# -gt 0 ]]; do
#     case "$1" in
#       --its-option) ...; shift 2 ;;
#       --) shift; passthrough=("$@"); break ;;
#       *) bench_option "$@"; shift "$bench_shift" ;;
#     esac
#   done
#
# shellcheck shell=bash disable=SC2034  # the variables set here are the caller's

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(dirname "$here")
data="$root/../shared/data"
build="$root/build-bench"
only=""
full=0
bench_name=$(basename "$0")

# bench_option ARGS...: one option every script takes (--out, --build, -h/--help; with
# bench_full_options=1 also --data, --only and --full). Sets bench_shift to the number of
# words it used; an unknown option ends the script with status 2.
bench_full_options=0
bench_option() {
  bench_shift=2
  case "$1" in
    --out) out=$2 ;;
    --build) build=$2 ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *)
      if [[ $bench_full_options -eq 1 ]]; then
        case "$1" in
          --data) data=$2; return ;;
          --only) only=$2; return ;;
          --full) full=1; bench_shift=1; return ;;
        esac
      fi
      echo "$bench_name: unknown option $1 (see --help)" >&2
      exit 2 ;;
  esac
}

# bench_configure: configures $build (Release, benchmarks on, tests off) if it has never been.
bench_configure() {
  if [[ ! -f "$build/CMakeCache.txt" ]]; then
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPGMCL_BUILD_BENCH=ON \
      -DPGMCL_BUILD_TESTS=OFF >/dev/null
  fi
}

# bench_build TARGET...: configures if needed, then builds the targets quietly.
bench_build() {
  bench_configure
  cmake --build "$build" -j2 --target "$@" >/dev/null
}

# want NAME: whether dataset NAME is in --only (all are when --only is not given).
want() { [[ -z "$only" || ",$only," == *",$1,"* ]]; }
