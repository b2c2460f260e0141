#!/usr/bin/env bash
# Quick start (1): install dependencies, build the massprops command (only it and its libraries),
# and print the mass properties of the default mesh: Keenan Crane's public-domain "Spot", a cow
# 2.6 m from nose to tail, so in metres (--unit m). Extra arguments go to massprops instead,
# e.g. `bash scripts/run.sh data/meshes/Moon.stl --density 7850 --format json`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=$(MASSPROPS_BUILD_TARGETS=massprops_cli bash "$root/scripts/build.sh" | tail -n 1)
if [ $# -eq 0 ]; then set -- "$root/data/meshes/spot.obj" --unit m; fi
exec "$build_dir/apps/massprops" "$@"
