#!/usr/bin/env bash
# Configures and builds the project into a build folder (default: build; build-asan with
# MASSPROPS_SANITIZE=ON). Installs missing dependencies first. Used by run.sh, test.sh and CI.
# MASSPROPS_BUILD_TARGETS="t1 t2" builds only those targets.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# ccache: paths relative to the checkout, so that another clone (CI's) reuses the cache.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$root} CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
bash "$root/scripts/install_deps.sh"

sanitize=${MASSPROPS_SANITIZE:-OFF}
build_dir=${MASSPROPS_BUILD_DIR:-$root/build}
if [ "$sanitize" = "ON" ] && [ -z "${MASSPROPS_BUILD_DIR:-}" ]; then build_dir=$root/build-asan; fi
build_type=${MASSPROPS_BUILD_TYPE:-Release}
# Benchmarks and the peer engines' comparison programs run once, in the Release build: under the
# sanitizers no test runs them, so they are not built there.
bench=ON
if [ "$sanitize" = "ON" ]; then build_type=RelWithDebInfo bench=OFF; fi

cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="$build_type" \
  -DMASSPROPS_SANITIZE="$sanitize" -DMASSPROPS_BUILD_BENCH="$bench" >/dev/null
# MASSPROPS_BUILD_TARGETS: only these targets (and what they need), e.g. the quick start's massprops_cli.
targets=()
for t in ${MASSPROPS_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}"
echo "$build_dir"
