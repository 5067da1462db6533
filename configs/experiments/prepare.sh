#!/usr/bin/env bash
# Turns the Radish / Freiburg SLAM-benchmark logs into the localisation cases that
# configs/experiments/{intel,aces,fr079,csail-raw}-{tracking,global}.yaml run on.
#
#   configs/experiments/prepare.sh DATA_DIR [PGMCL]
#
# DATA_DIR holds logs/ (intel-corrected.log.gz, aces-corrected.log.gz,
# freiburg-079-corrected.log.gz, csail-raw.clf.gz, csail-corrected.log.gz) and relations/
# (intel.relations), laid out as in the data README; missing logs are skipped with a note.
# PGMCL is the pgmcl binary (default build/release/pgmcl). Everything goes to out/cases/.
#
# Per corrected log (intel, aces, fr079), following the data README's recipe:
#   map.yaml      occupancy map at 5 cm from the corrected poses (pgmcl map)
#   truth.tum     the corrected FLASER poses = ground truth
#   realistic.log.gz  odometry = truth increments + Table 5.6 noise,
#                     alpha = (0.005, 0.0005, 0.005, 0.0005) (variance form), seed 1
#   harsh.log.gz      alpha = (0.05, 0.01, 0.05, 0.01), seed 1
#   biased.log.gz     realistic noise plus a systematic bias: translation reads 1.5 % long
#                     and the heading drifts 0.4 deg per metre, seed 1
# csail: the map comes from csail-corrected; raw.clf.gz is the real wheel odometry log
# (copied unchanged) and truth.log.gz the corrected log itself (copied unchanged: --truth
# and data.truth take a corrected log's scan poses, at the same stamps as raw.clf.gz).
# The experiment files select the odometry with data.log (realistic by default);
# `pgmcl run ... --set data.log=out/cases/intel/harsh.log.gz` switches profile.
set -euo pipefail
if [[ $# -lt 1 || $1 == -h || $1 == --help ]]; then
  # The comment block above, without its "# " and without any code.
  awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"
  [[ $# -lt 1 ]] && exit 2 || exit 0
fi
data=$1
cd "$(dirname "$0")/../.."
pgmcl=${2:-build/release/pgmcl}
out=out/cases
realistic=0.005,0.0005,0.005,0.0005
harsh=0.05,0.01,0.05,0.01

corrected_case() {  # name log
  local name=$1 log=$data/logs/$2
  if [[ ! -f $log ]]; then
    echo "prepare: $log not found, skipping $name" >&2
    return
  fi
  mkdir -p "$out/$name"
  "$pgmcl" map --log "$log" --resolution 0.05 --out "$out/$name/map.yaml"
  "$pgmcl" perturb --log "$log" --odom-noise $realistic --seed 1 \
    --out "$out/$name/realistic.log.gz" --truth-out "$out/$name/truth.tum"
  "$pgmcl" perturb --log "$log" --odom-noise $harsh --seed 1 \
    --out "$out/$name/harsh.log.gz" --truth-out "$out/$name/truth.tum"
  "$pgmcl" perturb --log "$log" --odom-noise $realistic --seed 1 \
    --scale-bias 0.015 --yaw-drift 0.4 \
    --out "$out/$name/biased.log.gz" --truth-out "$out/$name/truth.tum"
}

corrected_case intel intel-corrected.log.gz
corrected_case aces aces-corrected.log.gz
corrected_case fr079 freiburg-079-corrected.log.gz
if [[ -f $data/relations/intel.relations ]]; then
  cp "$data/relations/intel.relations" "$out/intel/intel.relations"
fi

if [[ -f $data/logs/csail-raw.clf.gz && -f $data/logs/csail-corrected.log.gz ]]; then
  mkdir -p "$out/csail-raw"
  "$pgmcl" map --log "$data/logs/csail-corrected.log.gz" --resolution 0.05 \
    --out "$out/csail-raw/map.yaml"
  cp "$data/logs/csail-raw.clf.gz" "$out/csail-raw/raw.clf.gz"
  cp "$data/logs/csail-corrected.log.gz" "$out/csail-raw/truth.log.gz"
else
  echo "prepare: csail-raw.clf.gz / csail-corrected.log.gz not found, skipping csail-raw" >&2
fi
echo "prepare: cases in $out/"
