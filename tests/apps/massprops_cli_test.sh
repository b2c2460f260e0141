#!/usr/bin/env bash
# End-to-end checks of the massprops command: exit status, error lines, output formats.
# Usage: massprops_cli_test.sh MASSPROPS_BINARY DATA_DIR
set -u
bin=$1
data=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
passes=0

check() {  # check NAME CONDITION-EXIT-CODE
  if [ "$2" -eq 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}

# 1. The default mesh: a table with the convention stated and the numbers.
"$bin" "$data/meshes/spot.obj" >"$tmp/out" 2>"$tmp/err"
check "spot exits 0" $?
grep -q "closed and consistently oriented" "$tmp/out"; check "spot closed" $?
grep -q "NEGATED products of inertia" "$tmp/out"; check "convention stated" $?
grep -q "physically valid  yes" "$tmp/out"; check "validity line" $?

# 2. JSON: parses, has the schema's keys, mass = density × volume, axes right-handed.
"$bin" "$data/meshes/cube_cup_quad.obj" --format json --density 2700 >"$tmp/json" 2>"$tmp/err"
check "json exits 0" $?
python3 - "$tmp/json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
keys = ["file", "volume", "mass", "density", "center_of_mass", "inertia_com", "principal_moments",
        "principal_axes", "surface_area", "mesh"]
assert all(k in d for k in keys), d.keys()
assert abs(d["volume"] - 4.24e-4) < 1e-12, d["volume"]
assert abs(d["mass"] - 2700 * d["volume"]) < 1e-12
a = d["principal_axes"]
det = (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
       + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
assert abs(det - 1) < 1e-12, det
m = d["principal_moments"]
assert m[0] <= m[1] <= m[2]
assert d["mesh"]["closed"] and d["mesh"]["boundary_edges"] == 0
PY
check "json content" $?

# 3. An open mesh is refused with what was found; --allow-open computes with a warning.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n' >"$tmp/open.obj"
"$bin" "$tmp/open.obj" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ]; check "open mesh exits 1" $?
grep -q "open.obj: open mesh: 3 boundary edges" "$tmp/err"; check "open mesh message" $?
[ ! -s "$tmp/out" ]; check "open mesh prints no number" $?
"$bin" "$tmp/open.obj" --allow-open >"$tmp/out" 2>"$tmp/err"
check "allow-open exits 0" $?
grep -q "warning: .*open.obj" "$tmp/err"; check "allow-open warns" $?

# 4. Inside-out mesh: named as such, no numbers.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n' >"$tmp/inverted.obj"
"$bin" "$tmp/inverted.obj" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ]; check "inverted exits 1" $?
grep -q "faces point inward" "$tmp/err"; check "inverted message" $?

# 5. Several files, one missing: the others still print; the status says something failed.
"$bin" "$data/meshes/Moon.stl" "$tmp/missing.stl" --format json >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ]; check "partial failure exits 1" $?
grep -q "missing.stl: cannot open" "$tmp/err"; check "missing file named" $?
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert d['file'].endswith('Moon.stl')" "$tmp/out"
check "good file still printed" $?

# 6. Impossible parameters.
"$bin" "$data/meshes/Moon.stl" --density -5 >"$tmp/out" 2>"$tmp/err"
[ $? -ne 0 ]; check "negative density refused" $?
grep -qi "density" "$tmp/err"; check "density named" $?
"$bin" "$data/meshes/Moon.stl" --format xml >"$tmp/out" 2>"$tmp/err"
[ $? -ne 0 ]; check "unknown format refused" $?

# 7. Same bits for 1 and 2 threads.
a=$("$bin" "$data/meshes/spot.obj" --format json --threads 1 | grep -v '"file"')
b=$("$bin" "$data/meshes/spot.obj" --format json --threads 2 | grep -v '"file"')
[ "$a" = "$b" ]; check "thread count does not change the output" $?

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
