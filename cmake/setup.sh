#!/usr/bin/env bash
# Installs the Debian packages pgmcl needs, only those missing. Run as root.
set -euo pipefail
packages=(
  build-essential cmake pkg-config          # toolchain
  libeigen3-dev libnanoflann-dev libyaml-cpp-dev zlib1g-dev libstb-dev   # libraries
  libcli11-dev                              # command line
  libgtest-dev libgmock-dev libbenchmark-dev   # tests and micro-benchmarks
  clang libclang-rt-14-dev libomp-dev       # libFuzzer targets (clang) and OpenMP for clang
  gnuplot-nox                               # benchmark plots
  python3                                   # the robustness suite (bench/robustness/run.py)
  python3-dev pybind11-dev python3-numpy    # the Python module (mcl/python)
  python3-pytest python3-matplotlib         # its tests and example
  # ROS 1 (PGMCL_WITH_ROS): pgmcl_node, rosbag I/O, and the end-to-end test's master,
  # rosbag play and Python client (tests/ros/node_e2e.py)
  libroscpp-dev libtf2-ros-dev librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev
  libgeometry-msgs-dev libtf2-msgs-dev libstd-srvs-dev libdiagnostic-msgs-dev
  python3-rosmaster python3-rosbag python3-rospy python3-geometry-msgs
  python3-sensor-msgs python3-nav-msgs python3-tf2-msgs python3-std-srvs
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "pgmcl setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "pgmcl setup: all packages present"
fi
