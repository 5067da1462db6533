#!/usr/bin/env bash
# pgmcl and MRPT 2.5's Monte Carlo localisation side by side, on the same logs, maps,
# (perturbed) odometry and particle counts, in one run:
#
#   bench/mrpt_side_by_side.sh [--data DIR] [--out DIR] [--build DIR] [--particles "1000 5000"]
#                              [--beams 90] [--repeat 3] [--pgmcl-only "500 2000 3000"] [--only LIST]
#                              [--full] [-- <pgmcl_sweep options>]
#
# --pgmcl-only  particle counts run for pgmcl alone: the second table compares each MRPT
#               setting with pgmcl's fastest setting of the same or lower ATE (issue 5's
#               target is stated at equal or lower error, not at equal particle count)
#
# Each setting runs pgmcl and MRPT alternately --repeat times; the table gives each one's
# median time per update and the ratio of the medians (a shared VM's speed drifts by up
# to 2x over minutes; alternating and taking medians keeps the ratio honest).
#
# MRPT runs through pgmcl_mrpt_harness (bench/mrpt/mrpt_harness.cpp: CMonteCarloLocalization2D
# + CParticleFilter, SIR, systematic resampling), which needs libmrpt-dev at configure time.
# The pf-localization app (mrpt-apps) is not used for figures: it writes no trajectory,
# carmen2rawlog drops timestamps and mislays FLASER beams without a PARAM line, and
# ros-map-yaml2mrpt snaps the origin; the harness feeds MRPT the exact data.
# Without MRPT this script says what to install and exits 0.
#
# Datasets: intel, aces, fr079 (first 1200 scans unless --full), csail; the maps come from
# `pgmcl map` (shared with bench/sweep.sh's output if --out is the same). Writes
# side_by_side.csv (one row per engine and setting) and prints time per update, ATE and
# the pgmcl/MRPT time ratio.
set -euo pipefail

source "$(dirname "$0")/common.sh"
bench_full_options=1
out="$root/results/bench/mrpt"
particles="1000 5000"
beams=90
repeat=3
pgmcl_only="500 2000 3000"
passthrough=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --particles) particles=$2; shift 2 ;;
    --beams) beams=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --pgmcl-only) pgmcl_only=$2; shift 2 ;;
    --) shift; passthrough=("$@"); break ;;
    *) bench_option "$@"; shift "$bench_shift" ;;
  esac
done

if ! ls /usr/lib/*/cmake/mrpt-slam/mrpt-slam-config.cmake >/dev/null 2>&1; then
  echo "mrpt_side_by_side: SKIPPED, MRPT is not installed."
  echo "  To run it: apt-get install mrpt-apps libmrpt-dev   (then re-run this script)"
  exit 0
fi
bench_configure
cmake "$build" -DPGMCL_BUILD_MRPT_HARNESS=ON >/dev/null  # also picks up a new libmrpt-dev
bench_build pgmcl pgmcl_sweep pgmcl_mrpt_harness
harness="$build/bench/pgmcl_mrpt_harness"
sweep="$build/bench/pgmcl_sweep"
pgmcl="$build/pgmcl"
if [[ ! -x "$harness" ]]; then
  echo "mrpt_side_by_side: SKIPPED, pgmcl_mrpt_harness was not built (is libmrpt-dev installed?)"
  exit 0
fi

mkdir -p "$out/maps"
csv="$out/side_by_side.csv"
pg_csv="$out/pgmcl_rows.csv"
rm -f "$csv" "$pg_csv"
log="$out/side_by_side.txt"
: >"$log"
max_scans=1200
[[ $full -eq 1 ]] && max_scans=0

for ds in intel aces fr079 csail; do
  want "$ds" || continue
  case $ds in
    intel) logf=intel-corrected.log.gz; truth=$logf; odo=(--perturb 1) ;;
    aces) logf=aces-corrected.log.gz; truth=$logf; odo=(--perturb 1) ;;
    fr079) logf=freiburg-079-corrected.log.gz; truth=$logf; odo=(--perturb 1) ;;
    csail) logf=csail-raw.clf.gz; truth=csail-corrected.log.gz
      odo=(--motion-noise 0.05,0.01,0.02,0.005) ;;  # real odometry (see sweep.sh)
  esac
  if [[ ! -f "$data/logs/$logf" || ! -f "$data/logs/$truth" ]]; then
    echo "== $ds: logs not found in $data/logs, skipped" | tee -a "$log"
    continue
  fi
  yaml="$out/maps/$ds.yaml"
  [[ -f "$yaml" ]] || "$pgmcl" map --log "$data/logs/$truth" --out "$yaml" | tee -a "$log"
  lim=()
  [[ $ds == fr079 && $max_scans -gt 0 ]] && lim=(--max-scans "$max_scans")
  for n in $particles $pgmcl_only; do
    for ((r = 1; r <= repeat; ++r)); do
      echo "== $ds, $n particles, $beams beams, run $r of $repeat" | tee -a "$log"
      "$sweep" --name "$ds" --map "$yaml" --log "$data/logs/$logf" --truth "$data/logs/$truth" \
        "${odo[@]}" "${lim[@]}" --particles "$n" --beams "$beams" --kinds isotropic \
        --csv "$pg_csv" "${passthrough[@]}" 2>&1 | tee -a "$log"
      [[ " $particles " == *" $n "* ]] || continue
      "$harness" --name "$ds" --map "$yaml" --log "$data/logs/$logf" --truth "$data/logs/$truth" \
        "${odo[@]}" "${lim[@]}" --particles "$n" --beams "$beams" --csv "$csv" 2>&1 | tee -a "$log"
    done
  done
done

# pgmcl rows in the harness's columns (time per performed measurement update, ATE).
awk -F, 'NR > 1 { printf "%s,pgmcl,%s,%.0f,%s,%s,%s,%s,%s\n", $1, $4, $18, $13, $15, $16, $19, $20 }' \
  "$pg_csv" >>"$csv"
{
  echo
  echo "Side by side (median of $repeat alternating runs; time per measurement update; ATE RMSE"
  echo "over every scan):"
  printf "%-8s %9s %6s | %10s %10s %7s | %9s %9s\n" dataset particles beams "pgmcl ms" "MRPT ms" \
    "MRPT/pg" "pgmcl ATE" "MRPT ATE"
  # Columns: 1 dataset 2 engine 3 particles 4 beams_used 5 updates 6 update_ms_mean 8 ATE.
  awk -F, '
    function median(list,   v, n, i, j, t) {
      n = split(list, v, " ")
      for (i = 2; i <= n; i++) { t = v[i] + 0; for (j = i - 1; j >= 1 && v[j] + 0 > t; j--) v[j + 1] = v[j]; v[j + 1] = t }
      return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
    }
    NR > 1 { k = $1 "," $3; g = $2; ms[g, k] = ms[g, k] " " $6; ate[g, k] = ate[g, k] " " $8; b[g, k] = $4
             if (g == "pgmcl" && !(k in seen)) { seen[k] = 1; order[++n] = k } }
    END { for (i = 1; i <= n; i++) { k = order[i]; if (!(("mrpt", k) in ms)) continue; split(k, a, ",")
            pt = median(ms["pgmcl", k]); mt = median(ms["mrpt", k])
            printf "%-8s %9s %3s/%-3s | %10.3f %10.3f %7.1f | %8.3fm %8.3fm\n", a[1], a[2], b["pgmcl", k],
              b["mrpt", k], pt, mt, (pt > 0 ? mt / pt : 0), median(ate["pgmcl", k]), median(ate["mrpt", k]) }
          # Same or lower ATE: each MRPT setting against the fastest pgmcl setting of the
          # same dataset whose median ATE is not higher.
          print "\nSame or lower ATE (each MRPT setting against the fastest pgmcl setting that is at"
          print "least as accurate on that log):"
          printf "%-8s %14s %14s | %10s %10s %7s\n", "dataset", "MRPT particles", "pgmcl particles", \
            "pgmcl ms", "MRPT ms", "MRPT/pg"
          for (km in ms) { split(km, e, SUBSEP); if (e[1] != "mrpt") continue; split(e[2], a, ",")
            mt = median(ms["mrpt", e[2]]); ma = median(ate["mrpt", e[2]]); best = -1; bn = ""
            for (kp in ms) { split(kp, f, SUBSEP); if (f[1] != "pgmcl") continue; split(f[2], c, ",")
              if (c[1] != a[1] || median(ate["pgmcl", f[2]]) > ma) continue
              t = median(ms["pgmcl", f[2]]); if (best < 0 || t < best) { best = t; bn = c[2] } }
            if (best > 0) line[a[1] "," a[2] + 0] = sprintf("%-8s %14s %14s | %10.3f %10.3f %7.1f", a[1], a[2], bn, best, mt, mt / best)
            else line[a[1] "," a[2] + 0] = sprintf("%-8s %14s %14s | %10s %10.3f %7s", a[1], a[2], "none", "-", mt, "-") }
          for (i = 1; i <= n; i++) if (order[i] in line) print line[order[i]] }' \
    "$csv"
  echo "(beams: pgmcl/MRPT per update; MRPT/pg = how many times longer MRPT takes per update)"
} | tee -a "$log"
echo "mrpt_side_by_side: wrote $csv and $log"
