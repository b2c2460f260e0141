#!/usr/bin/env bash
# Quick start (1): install dependencies, build, and print the mass properties of the default mesh
# (Keenan Crane's public-domain "Spot", data/meshes/spot.obj). Extra arguments go to massprops,
# e.g. `bash scripts/run.sh data/meshes/Moon.stl --density 7850 --format json`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=$(bash "$root/scripts/build.sh" | tail -n 1)
if [ $# -eq 0 ]; then set -- "$root/data/meshes/spot.obj"; fi
exec "$build_dir/apps/massprops" "$@"
