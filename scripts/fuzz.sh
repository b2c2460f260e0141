#!/usr/bin/env bash
# Fuzzes the hand-written mesh parsers, the rbsim scene parser and the robot readers (URDF,
# SDFormat, MJCF) with libFuzzer (clang, AddressSanitizer, UBSan), SECONDS in all (default 60: half
# on the meshes, a quarter each on the scenes and the robots), starting from the small meshes in
# data/, tests/fuzz/corpus/, tests/fuzz/scene_corpus/ and the robot fixtures.
# A crash leaves its input as build-fuzz/crash-* and fails the script.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# ccache: paths relative to the checkout, so that another clone (CI's) reuses the cache.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$root} CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
seconds=${1:-60}
bash "$root/scripts/install_deps.sh"
build=$root/build-fuzz
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER="$(command -v clang++ || command -v clang++-14)" -DMASSPROPS_BUILD_FUZZERS=ON -DMASSPROPS_BUILD_TESTS=OFF \
  -DMASSPROPS_BUILD_APPS=ON -DMASSPROPS_BUILD_BENCH=OFF -DMASSPROPS_BUILD_PYTHON=OFF -DMASSPROPS_WITH_CAD=OFF \
  -DMASSPROPS_WITH_CGAL=OFF -DMASSPROPS_WITH_ASSIMP=OFF >/dev/null  # the parsers need neither: CGAL's units take minutes here
cmake --build "$build" --target mesh_parsers_fuzzer scene_parser_fuzzer robot_readers_fuzzer
corpus=$build/corpus
mkdir -p "$corpus"
cp "$root"/tests/fuzz/corpus/* "$corpus"/
for f in Moon.stl HalfDonut_binary.stl HalfDonut_ascii.stl hollow_sphere.off; do cp "$root/data/meshes/$f" "$corpus"/; done
cd "$build"
./mesh_parsers_fuzzer -max_total_time="$((seconds / 2))" -max_len=65536 -timeout=10 -rss_limit_mb=4096 \
  -print_final_stats=1 "$corpus" 2>&1 | tail -n 25
scenes=$build/scene_corpus
mkdir -p "$scenes"
cp "$root"/tests/fuzz/scene_corpus/* "$scenes"/
./scene_parser_fuzzer -max_total_time="$((seconds / 4))" -max_len=8192 -timeout=10 -rss_limit_mb=4096 \
  -print_final_stats=1 "$scenes" 2>&1 | tail -n 25
robots=$build/robot_corpus
mkdir -p "$robots"
cp "$root"/tests/robot/field/*.urdf "$root"/tests/robot/field/mjcf/*.xml "$robots"/
cp "$root"/tests/robot/field/constraints/*.xml "$root"/tests/robot/field/constraints/*.urdf \
  "$root"/tests/robot/field/constraints/*.sdf "$robots"/  # couplings, loops and tendons
cp "$root"/data/robots/quadruped/quadruped.urdf "$root"/data/robots/quadruped/quadruped.sdf "$robots"/
./robot_readers_fuzzer -max_total_time="$((seconds / 4))" -max_len=8192 -timeout=10 -rss_limit_mb=4096 \
  -print_final_stats=1 "$robots" 2>&1 | tail -n 25
