#!/usr/bin/env bash
# The whole test suite, as the README's second command and .ci/run run it:
#   1. Release build, warnings as errors, OpenMP on, ROS 1 on; every test (closed loops with
#      2 threads, pgmcl_node under a real master), the Python module's pytest suites and
#      example included.
#   2. Debug build (-O1) under AddressSanitizer + UBSan, OpenMP off (proves the serial build),
#      ROS 1 off (its edges are tested in stage 1; under ASan the end-to-end test would
#      replay a whole bag through the node).
#   3. Install, then build and run a consumer project against find_package(pgmcl), and
#      import the installed Python module.
#   4. Bounded libFuzzer runs of each fuzz target (clang).
set -euo pipefail
cd "$(dirname "$0")/.."
bash cmake/setup.sh
jobs=${PGMCL_JOBS:-2}
fuzz_seconds=${PGMCL_FUZZ_SECONDS:-30}
root=$PWD
t0=$SECONDS
stage_start=$SECONDS
stage_done() {  # prints how long the stage that just ended took (CI budget: 30 min in all)
  echo "== $1 done in $((SECONDS - stage_start)) s"
  stage_start=$SECONDS
}

echo "== [1/4] Release build + tests"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DPGMCL_WERROR=ON \
  -DPGMCL_WITH_PYTHON=ON -DPGMCL_WITH_ROS=ON >/dev/null
cmake --build build/release -j"$jobs"
if [ ! -x build/release/pgmcl_node ]; then  # setup.sh installed ROS: it must have been found
  echo "pgmcl_node was not built (see the PGMCL_WITH_ROS message of the configure step)" >&2
  exit 1
fi
ctest --test-dir build/release --output-on-failure -j"$jobs"
stage_done "[1/4]"

echo "== [2/4] Debug + ASan/UBSan build + tests (serial, no OpenMP)"
# -g1 (line tables only): sanitizer reports keep file:line, and the stage compiles ~25 %
# faster than with full -g (its compile time is most of CI's 30-minute budget).
# No Python module here: an ASan-instrumented extension needs the sanitizer runtime preloaded
# into an uninstrumented interpreter; the module is built and tested in stage 1.
cmake -S . -B build/asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" \
  -DPGMCL_SANITIZE=ON -DPGMCL_USE_OPENMP=OFF -DPGMCL_WERROR=ON -DPGMCL_BUILD_BENCH=OFF \
  -DPGMCL_WITH_PYTHON=OFF -DPGMCL_WITH_ROS=OFF >/dev/null
cmake --build build/asan -j"$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build/asan --output-on-failure -j"$jobs"
stage_done "[2/4]"

echo "== [3/4] Install + find_package(pgmcl) consumers (whole package; pgmcl::mcl alone)"
rm -rf build/install build/consumer
cmake --install build/release --prefix build/install >/dev/null
cmake -S mcl/examples/consumer -B build/consumer -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$root/build/install" >/dev/null
cmake --build build/consumer -j"$jobs"
build/consumer/pgmcl_consumer "$root/data"
# The engine alone needs none of the file-format libraries: their CMake packages are
# disabled, and the program must not load them at run time either.
rm -rf build/in_memory
cmake -S mcl/examples/in_memory -B build/in_memory -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$root/build/install" -DCMAKE_DISABLE_FIND_PACKAGE_yaml-cpp=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_ZLIB=ON -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON >/dev/null
cmake --build build/in_memory -j"$jobs"
if readelf -d build/in_memory/pgmcl_in_memory | grep -E "NEEDED.*(yaml-cpp|libz\.|stb)"; then
  echo "pgmcl_in_memory links a file-format library" >&2
  exit 1
fi
build/in_memory/pgmcl_in_memory
# The Python module from the install prefix alone: Debian's python3, another folder, only
# PYTHONPATH pointing into the prefix (mcl/python/README.md, "Build, path, install").
pydir=$(sed -n 's/^PGMCL_PYTHON_INSTALL_DIR:STRING=//p' build/release/CMakeCache.txt)
(cd /tmp && PYTHONPATH="$root/build/install/$pydir" /usr/bin/python3 -c "
import pgmcl
assert pgmcl.__file__.startswith('$root/build/install/'), pgmcl.__file__
c = pgmcl.Config({'filter.particles': 500})
print('pgmcl', pgmcl.__version__, 'from', pgmcl.__file__, '- filter.particles', c['filter.particles'])")
stage_done "[3/4]"

echo "== [4/4] Fuzzing (${fuzz_seconds}s per target)"
if [ -d tests/fuzz ] && command -v clang++ >/dev/null; then
  CXX=clang++ cmake -S . -B build/fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DPGMCL_FUZZ=ON \
    -DPGMCL_BUILD_TESTS=OFF -DPGMCL_BUILD_BENCH=OFF -DPGMCL_USE_OPENMP=OFF \
    -DPGMCL_WITH_PYTHON=OFF -DPGMCL_WITH_ROS=OFF >/dev/null
  cmake --build build/fuzz -j"$jobs" --target pgmcl_fuzzers
  bash tests/fuzz/run_all.sh build/fuzz "$fuzz_seconds"
else
  echo "no fuzz targets yet"
fi
stage_done "[4/4]"
echo "== all test stages passed in $((SECONDS - t0)) s"
