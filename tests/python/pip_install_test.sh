#!/usr/bin/env bash
# `pip install --no-build-isolation --no-index .` in a fresh venv made by Debian's interpreter
# (with its site packages: numpy, setuptools, wheel, mypy), then the installed module: numbers
# against the closed form, `python -m massprops` against the build's command, stubtest, pytest's
# packaging tests. A third build (CMake under build-pip/, mostly ccache hits of build/).
#   pip_install_test.sh [BUILD_DIR]   (the build whose massprops the module is compared with)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
(cd "$root" && "$work/venv/bin/pip" install --no-build-isolation --no-index . -q)
cd "$work"  # away from the source tree: the installed package, not python/
py="$work/venv/bin/python"
"$py" - "$root/data/meshes/t_handle.obj" <<'PY'
import sys, massprops
assert massprops.__file__.startswith(sys.prefix), massprops.__file__
r = massprops.load(sys.argv[1], unit="m", repair=True)   # the repair: CGAL, found beside the module
v = 0.08 * 0.02 * 0.02 + 0.02 * 0.06 * 0.02
assert abs(r.volume - v) <= 1e-14 * v and abs(r.mass - 1000 * v) <= 1e-14 * 1000 * v, (r.volume, r.mass)
# A PNG picture through the raster plugin installed in the package (librsvg, loaded on first use).
import os, tempfile
png = os.path.join(tempfile.mkdtemp(), "t.png")
r.picture(png)
head = open(png, "rb").read(8)
assert head == b"\x89PNG\r\n\x1a\n", head
print("pip_install_test: installed module computes the T-handle and draws it as PNG")
PY
MASSPROPS_CLI="$build/apps/massprops" MASSPROPS_DATA="$root/data" \
  "$py" -m pytest -q -p no:cacheprovider "$root/tests/python/test_packaging.py"
echo "pip_install_test: pip install, python -m massprops, stubs and docstrings work"
