#!/usr/bin/env bash
# The README's first command: install what is missing, build in Release, run the demo.
# The demo turns the bundled Intel Research Lab log into a localisation case (map from the
# SLAM-corrected poses, seeded noisy odometry), localises on it, and simulates and
# localises one UTM-30LX scene. Everything it writes goes to out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash cmake/setup.sh
jobs=${PGMCL_JOBS:-2}
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DPGMCL_WITH_PYTHON=ON \
  -DPGMCL_WITH_ROS=ON >/dev/null
cmake --build build/release -j"$jobs" --target pgmcl
# The Python module (build/release/python/pgmcl) when its packages are there (setup.sh).
python=$(sed -n 's/^PGMCL_PYTHON_BUILT:INTERNAL=//p' build/release/CMakeCache.txt)
if [[ $python == ON ]]; then
  cmake --build build/release -j"$jobs" --target pgmcl_python
fi
pgmcl=build/release/pgmcl
out=out/demo
mkdir -p "$out/intel"

echo "== Intel Research Lab (real scans, corrected poses as truth, realistic noisy odometry)"
$pgmcl map --log data/logs/intel-corrected.log.gz --resolution 0.05 --out "$out/intel/map.yaml"
$pgmcl perturb --log data/logs/intel-corrected.log.gz --odom-noise 0.005,0.0005,0.005,0.0005 \
  --seed 1 --out "$out/intel/raw.log.gz" --truth-out "$out/intel/truth.tum"
$pgmcl run configs/experiments/intel-demo.yaml --out "$out/intel/tracking"

ros=$(sed -n 's/^PGMCL_ROS_BUILT:INTERNAL=//p' build/release/CMakeCache.txt)
if [[ $ros == ON ]]; then
  echo "== The same case as a ROS 1 bag: pgmcl convert, then pgmcl localize --bag (no master)"
  $pgmcl convert --log "$out/intel/raw.log.gz" --out "$out/intel/raw.bag"
  $pgmcl localize --map "$out/intel/map.yaml" --bag "$out/intel/raw.bag" \
    --truth "$out/intel/truth.tum" --set motion.noise.a1=0.01 --set motion.noise.a2=0.001 \
    --set motion.noise.a3=0.01 --set motion.noise.a4=0.001 --set likelihood.table.kind=isotropic \
    --set filter.particles=1000 --seed 1 --quiet --out "$out/intel/bag"
else
  echo "== (ROS 1 not built: no bag conversion; see the PGMCL_WITH_ROS message of cmake)"
fi

echo "== Simulated UTM-30LX scene (the paper's sensor, 1081 beams)"
$pgmcl run configs/experiments/lab.yaml --out "$out/utm-lab"

if [[ $python == ON ]]; then
  echo "== From Python (README): the Intel case again, ATE RMSE in metres"
  PYTHONPATH=build/release/python /usr/bin/python3 -c "import pgmcl; print(pgmcl.localize('out/demo/intel/map.yaml', 'out/demo/intel/raw.log.gz', truth='out/demo/intel/truth.tum', seed=1).metrics['ate_rmse_m'])"
fi

echo "== Results in $out/ (trajectory.tum, metrics.yaml, overlay.png, error.png per run)"
