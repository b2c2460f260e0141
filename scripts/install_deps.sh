#!/usr/bin/env bash
# Installs every Debian 12 package this project builds, tests and benchmarks with.
# Idempotent: when everything is already installed it only runs dpkg queries (well under a second).
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev zlib1g-dev libpng-dev libassimp-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libtbb-dev libfast-float-dev
  python3-dev python3-numpy python3-pytest pybind11-dev python3-stl python3-distributed python3-pandas
  python3-venv python3-pip python3-setuptools python3-wheel python3-mypy
  librsvg2-dev chromium
  libocct-data-exchange-dev libocct-modeling-algorithms-dev libocct-ocaf-dev
  libpugixml-dev liburdfdom-dev liburdfdom-tools libsdformat-dev libmujoco-dev libbullet-dev
  clang-14 libclang-rt-14-dev clang-format-14
  python3 gnuplot-nox libgnuplot-iostream-dev libboost-iostreams-dev libboost-filesystem-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# Node.js and npm run the Khronos glTF validator and the browser test in rbsim's tests; the machine image usually has
# them (not from Debian), so Debian's are installed only when there are none.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then missing+=(nodejs npm); fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "install_deps: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# From the npm registry at the versions pinned in each package-lock.json: the glTF validator and
# playwright-core (which drives Debian's chromium) for the tests, three.js and esbuild for the
# check that the committed viewer bundle is current.
root=$(cd "$(dirname "$0")/.." && pwd)
for pinned in tests/rbsim:gltf-validator tests/rbsim:playwright-core apps/rbsim/viewer:three apps/rbsim/viewer:esbuild; do
  dir=${pinned%%:*} package=${pinned##*:}
  if [ ! -f "$root/$dir/node_modules/$package/package.json" ]; then
    echo "install_deps: npm ci in $dir ($package)" >&2
    (cd "$root/$dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
  fi
done
