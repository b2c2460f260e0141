#!/usr/bin/env bash
# Builds the libraries and massprops without assimp, CGAL, OpenCASCADE and librsvg (the core needs
# only Eigen) and checks that what needs them says so: an OBJ is computed, a glTF file, a STEP file,
# --repair and a PNG picture are refused with the reason. Exit 0 when all of that holds.
#   check_minimal.sh [BUILD_DIR]   (default: build-minimal)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# ccache: paths relative to the checkout, so that another clone (CI's) reuses the cache.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$root} CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-1}
build=${1:-$root/build-minimal}
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMASSPROPS_WITH_ASSIMP=OFF \
  -DMASSPROPS_WITH_CGAL=OFF -DMASSPROPS_WITH_CAD=OFF -DMASSPROPS_WITH_RSVG=OFF -DMASSPROPS_BUILD_TESTS=OFF -DMASSPROPS_BUILD_BENCH=OFF -DMASSPROPS_BUILD_PYTHON=OFF >/dev/null
cmake --build "$build" --target massprops_cli >/dev/null
bin=$build/apps/massprops
"$bin" "$root/data/meshes/t_handle.obj" --format csv -q | tail -n 1 | grep -q ',m,5.6e-05,0.056,' \
  || { echo "check_minimal: the T-handle was not computed"; exit 1; }
set +e
"$bin" "$root/data/meshes/box_0.1x0.2x0.3.gltf" -q 2>"$build/err"; status=$?
grep -q "configured without assimp" "$build/err" && [ $status -eq 1 ] \
  || { echo "check_minimal: glTF without assimp: exit $status, $(cat "$build/err")"; exit 1; }
"$bin" "$root/data/cad/drilled_plate.step" -q 2>"$build/err"; status=$?
grep -q "configured without OpenCASCADE" "$build/err" && [ $status -eq 1 ] \
  || { echo "check_minimal: STEP without OpenCASCADE: exit $status, $(cat "$build/err")"; exit 1; }
"$bin" "$root/data/meshes/t_handle.obj" --repair -q 2>"$build/err"; status=$?
grep -q "needs CGAL" "$build/err" && [ $status -eq 1 ] \
  || { echo "check_minimal: --repair without CGAL: exit $status, $(cat "$build/err")"; exit 1; }
"$bin" "$root/data/meshes/t_handle.obj" --picture "$build/t.png" -q 2>"$build/err"; status=$?
grep -q "no librsvg" "$build/err" && [ $status -eq 2 ] && [ ! -e "$build/t.png" ] \
  || { echo "check_minimal: a PNG picture without librsvg: exit $status, $(cat "$build/err")"; exit 1; }
echo "check_minimal: the build without assimp, CGAL, OpenCASCADE and librsvg computes, and says what it cannot do"
