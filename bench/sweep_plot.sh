#!/usr/bin/env bash
# Plots a pgmcl_sweep CSV: one panel per dataset, filter time per scan (ms, log axis)
# against ATE RMSE (cm), one colour per table kind, the Pareto front as a line.
#   bench/sweep_plot.sh sweep.csv sweep.png
# Needs gnuplot (Debian gnuplot-nox); without it, says so and exits 0.
set -euo pipefail
csv=$1
png=$2
if ! command -v gnuplot >/dev/null; then
  echo "sweep_plot: gnuplot not found (apt-get install gnuplot-nox); no plot written"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Columns: 1 dataset 2 study 3 kind 4 particles 5 beams ... 14 ms_per_scan 19 ate_rmse_m 22 pareto
mapfile -t sets < <(awk -F, 'NR > 1 && $2 == "grid" && !seen[$1]++ { print $1 }' "$csv")
if [[ ${#sets[@]} -eq 0 ]]; then
  echo "sweep_plot: no grid rows in $csv"
  exit 0
fi
for ds in "${sets[@]}"; do
  for kind in isotropic oriented offset; do
    awk -F, -v d="$ds" -v k="$kind" 'NR > 1 && $1 == d && $2 == "grid" && $3 == k {
      print $19 * 100, $14, $4 "/" $5 }' "$csv" >"$tmp/$ds.$kind.dat"
  done
  awk -F, -v d="$ds" 'NR > 1 && $1 == d && $2 == "grid" && $22 == 1 { print $19 * 100, $14 }' \
    "$csv" | sort -g -k2 >"$tmp/$ds.pareto.dat"
done

n=${#sets[@]}
cols=$((n < 3 ? n : 3))
rows=$(((n + cols - 1) / cols))
{
  echo "set terminal pngcairo size $((cols * 560)),$((rows * 430)) font ',10'"
  echo "set output '$png'"
  echo "set multiplot layout $rows,$cols title 'pgmcl: filter time per scan vs ATE (grid study; line = Pareto front; runs with ATE > 1 m off chart)'"
  echo "set logscale y"
  echo "set xlabel 'ATE RMSE (cm)'"
  echo "set ylabel 'time per scan (ms)'"
  echo "set grid"
  echo "set key top left box opaque"
  for ds in "${sets[@]}"; do
    echo "set title '$ds'"
    # Every run up to 100 cm: a diverged run would squeeze the others into one pixel.
    xmax=$(awk -F, -v d="$ds" 'NR > 1 && $1 == d && $2 == "grid" && $19 * 100 <= 100 &&
      $19 * 100 > m { m = $19 * 100 } END { printf "%.2f", m * 1.1 + 0.1 }' "$csv")
    echo "set xrange [0:$xmax]"
    echo "plot '$tmp/$ds.isotropic.dat' using 1:2 with points pt 7 ps 0.9 lc rgb '#1f77b4' title 'isotropic', \\"
    echo "     '$tmp/$ds.oriented.dat' using 1:2 with points pt 5 ps 0.9 lc rgb '#ff7f0e' title 'oriented', \\"
    echo "     '$tmp/$ds.offset.dat' using 1:2 with points pt 9 ps 1.0 lc rgb '#2ca02c' title 'offset', \\"
    echo "     '$tmp/$ds.pareto.dat' using 1:2 with linespoints lw 2 pt 6 ps 1.6 lc rgb 'black' title 'Pareto'"
  done
  echo "unset multiplot"
} >"$tmp/plot.gp"
# An empty kind file makes gnuplot warn; the warnings are harmless.
gnuplot "$tmp/plot.gp" 2> >(grep -v 'empty\|no valid points' >&2 || true)
echo "sweep_plot: wrote $png"
