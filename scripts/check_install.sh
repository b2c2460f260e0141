#!/usr/bin/env bash
# Installs the build into a fresh temporary prefix, builds tests/consumer against it with
# find_package(massprops) and runs it, and runs the installed massprops and the installed Python
# module on a glTF file (read through the assimp plugin installed beside the library). Exit 0 when all of it works.
#   check_install.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
prefix=$(mktemp -d)
work=$(mktemp -d)
trap 'rm -rf "$prefix" "$work"' EXIT
cmake --install "$build" --prefix "$prefix" >/dev/null
cmake -S "$root/tests/consumer" -B "$work" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work" >/dev/null
"$work/consumer" "$root/data"
bash "$root/tests/consumer/reader_only_test.sh" "$work/reader_only" "$(echo "$prefix"/lib*/libmassprops_io.so)" "$root/data/meshes"
# The installed command, away from the build tree, reads glTF as the build tree does.
env -u MASSPROPS_ASSIMP_PLUGIN "$prefix/bin/massprops" "$root/data/meshes/box_0.1x0.2x0.3.gltf" --format csv -q \
  | tail -n 1 | grep -q '^"[^"]*box_0.1x0.2x0.3.gltf",m,0.0060000017' \
  || { echo "check_install: the installed massprops did not read the glTF box"; exit 1; }
# ... and STEP through the CAD plugin installed beside the library (a 40 × 40 × 10 mm plate with a
# hole of radius 8: 14 389.4 mm^3, 14.389 g at 1000 kg/m^3): the answer is the exact B-rep, its check
# mesh within 1e-3 of it).
env -u MASSPROPS_CAD_PLUGIN "$prefix/bin/massprops" "$root/data/cad/drilled_plate.step" --format json -q \
  | /usr/bin/python3 -c 'import json, math, sys; r = json.load(sys.stdin); v = 40 * 40 * 10 - math.pi * 64 * 10
assert r["brep"]["result"] == "brep" and abs(r["volume"] * 1e9 - v) < 1e-9 * v, r
assert abs(r["brep"]["mesh"]["volume"] * 1e9 - v) < 1e-3 * v, r' \
  || { echo "check_install: the installed massprops did not read the STEP plate"; exit 1; }
# ... and draws a PNG through the raster plugin installed beside the library (librsvg, loaded on
# first use): a PNG file's signature and a picture of at least 400 px a side.
env -u MASSPROPS_RASTER_PLUGIN "$prefix/bin/massprops" "$root/data/meshes/spot.obj" --unit m -q --picture "$work/spot.png" >/dev/null
/usr/bin/python3 -c 'import struct, sys; d = open(sys.argv[1], "rb").read(24)
assert d[:8] == b"\x89PNG\r\n\x1a\n", d[:8]
w, h = struct.unpack(">II", d[16:24]); assert w >= 400 and h >= 400, (w, h)' "$work/spot.png" \
  || { echo "check_install: the installed massprops did not draw a PNG"; exit 1; }
# The installed Python module, from the prefix's dist-packages, with Debian's interpreter.
pydir=$(echo "$prefix"/lib/python3*/dist-packages)
env -u MASSPROPS_ASSIMP_PLUGIN PYTHONPATH="$pydir" /usr/bin/python3 -c "
import massprops, sys
assert massprops.__file__.startswith('$prefix'), massprops.__file__
r = massprops.load('$root/data/meshes/box_0.1x0.2x0.3.gltf')
assert abs(r.mass - 6.0) < 1e-5 and abs(r.inertia_com[0][0] - 0.065) < 1e-7, r
" || { echo "check_install: the installed Python module did not work"; exit 1; }
"$prefix/bin/massprops" --version
"$prefix/bin/rbsim" --version
echo "check_install: installed package, find_package consumer glTF and STEP reading and PNG pictures work"
