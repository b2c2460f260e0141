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
grep -q "open.obj: open mesh: 3 boundary edges in 1 hole" "$tmp/err"; check "open mesh message" $?
[ ! -s "$tmp/out" ]; check "open mesh prints no number" $?
"$bin" "$tmp/open.obj" --allow-open >"$tmp/out" 2>"$tmp/err"
check "allow-open exits 0" $?
grep -q "warning: .*open.obj" "$tmp/err"; check "allow-open warns" $?

# 4. Inside-out mesh: named as such, no numbers.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n' >"$tmp/inverted.obj"
"$bin" "$tmp/inverted.obj" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ]; check "inverted exits 1" $?
grep -q "faces point inward" "$tmp/err"; check "inverted message" $?

# 4b. A closed surface that encloses nothing: named, no number.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n' >"$tmp/flat.obj"
"$bin" "$tmp/flat.obj" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ]; check "zero volume exits 1" $?
grep -q "flat.obj: the volume is zero up to rounding" "$tmp/err"; check "zero volume named" $?

# 5. Several files, one missing: the others still print; the status says something failed.
"$bin" "$data/meshes/Moon.stl" "$tmp/missing.stl" --format json >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ]; check "partial failure exits 1" $?
grep -q "missing.stl: cannot open" "$tmp/err"; check "missing file named" $?
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert len(d) == 1 and d[0]['file'].endswith('Moon.stl')" "$tmp/out"
check "good file still printed, in an array (several inputs were given)" $?

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

# 8. Units and --mass: millimetres scale volume by 1e-9 and inertia by 1e-15 at equal density;
#    --mass fixes the total.
"$bin" "$data/meshes/Moon.stl" --format json >"$tmp/m.json" && \
"$bin" "$data/meshes/Moon.stl" --format json --unit mm >"$tmp/mm.json" && \
"$bin" "$data/meshes/Moon.stl" --format json --unit in --mass 2.5 >"$tmp/mass.json"
check "unit runs" $?
python3 - "$tmp/m.json" "$tmp/mm.json" "$tmp/mass.json" <<'PY'
import json, sys
m, mm, ms = (json.load(open(p)) for p in sys.argv[1:])
rel = lambda a, b: abs(a - b) <= 1e-12 * abs(b)
assert rel(mm["volume"], m["volume"] * 1e-9), (mm["volume"], m["volume"])
assert rel(mm["inertia_com"][0][1], m["inertia_com"][0][1] * 1e-15)
assert all(rel(a, b * 1e-3) for a, b in zip(mm["center_of_mass"], m["center_of_mass"]))
assert mm["unit"] == "mm"
assert rel(ms["mass"], 2.5) and rel(ms["volume"], m["volume"] * 0.0254 ** 3)
PY
check "unit and mass scaling" $?
"$bin" "$data/meshes/Moon.stl" --mass 1 --density 2 >"$tmp/out" 2>"$tmp/err"
[ $? -ne 0 ]; check "--mass excludes --density" $?

# 9. A part 300 units across, read as metres: the warning names the likely unit.
printf 'v 0 0 0\nv 300 0 0\nv 0 300 0\nv 0 0 300\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >"$tmp/big.obj"
"$bin" "$tmp/big.obj" >"$tmp/out" 2>"$tmp/err"
check "big part exits 0" $?
grep -q "warning: .*big.obj: the part is 519.6 m across.*--unit mm" "$tmp/err"; check "unit warning" $?

# 10. Robot descriptions parse as XML and carry the JSON's numbers; CSV has its header.
"$bin" "$data/meshes/spot.obj" --format json >"$tmp/spot.json"
for f in urdf sdf mjcf; do "$bin" "$data/meshes/spot.obj" --format $f >"$tmp/spot.$f"; done
python3 - "$tmp/spot.json" "$tmp/spot.urdf" "$tmp/spot.sdf" "$tmp/spot.mjcf" <<'PY'
import json, sys, math
import xml.etree.ElementTree as ET
j = json.load(open(sys.argv[1]))
I, c, m = j["inertia_com"], j["center_of_mass"], j["mass"]
same = lambda a, b: a == b or abs(a - b) <= 1e-15 * max(abs(a), abs(b))
u = ET.fromstring(open(sys.argv[2]).read().split("-->", 1)[1])
assert same(float(u.find("mass").get("value")), m)
ii = u.find("inertia")
for k, (r, s) in {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1), "iyz": (1, 2), "izz": (2, 2)}.items():
    assert same(float(ii.get(k)), I[r][s]), k
assert all(same(float(a), b) for a, b in zip(u.find("origin").get("xyz").split(), c))
s = ET.fromstring(open(sys.argv[3]).read().split("-->", 1)[1])
assert same(float(s.find("mass").text), m)
assert same(float(s.find("inertia/ixy").text), I[0][1])
assert all(same(float(a), b) for a, b in zip(s.find("pose").text.split()[:3], c))
x = ET.fromstring(open(sys.argv[4]).read().split("-->", 1)[1])
w, qx, qy, qz = map(float, x.get("quat").split())
d = list(map(float, x.get("diaginertia").split()))
R = [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * w), 2 * (qx * qz + qy * w)],
     [2 * (qx * qy + qz * w), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * w)],
     [2 * (qx * qz - qy * w), 2 * (qy * qz + qx * w), 1 - 2 * (qx * qx + qy * qy)]]
scale = max(abs(v) for row in I for v in row)
for r in range(3):
    for t in range(3):
        v = sum(R[r][k] * d[k] * R[t][k] for k in range(3))
        assert abs(v - I[r][t]) < 1e-12 * scale, (r, t, v, I[r][t])
assert same(float(x.get("mass")), m)
PY
check "urdf/sdf/mjcf round trip" $?
"$bin" "$data/meshes/spot.obj" "$data/meshes/Moon.stl" --format csv >"$tmp/out.csv"
python3 - "$tmp/out.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2 and rows[1]["file"].endswith("Moon.stl")
assert {"mass_kg", "com_x_m", "ixy", "i3", "closed"} <= set(rows[0])
PY
check "csv" $?

# 11. -o writes the file whole; a failed run leaves no file behind.
"$bin" "$data/meshes/spot.obj" --format json -o "$tmp/result.json" >"$tmp/out"
check "-o exits 0" $?
python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$tmp/result.json"; check "-o file is whole JSON" $?
[ ! -s "$tmp/out" ]; check "-o leaves stdout empty" $?
"$bin" "$tmp/open.obj" --format json -o "$tmp/none.json" 2>/dev/null
[ ! -e "$tmp/none.json" ] && [ ! -e "$tmp/none.json.tmp-massprops" ]; check "no file on failure" $?

# 12. Nested shells facing the same way are refused; --repair makes the inner one a cavity.
"$bin" "$data/meshes/hollow_sphere.off" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ]; check "overlapping shells refused" $?
grep -q "lies inside shell 1 and both face outward" "$tmp/err"; check "overlap named" $?
"$bin" "$data/meshes/hollow_sphere.off" --repair --format json >"$tmp/hs.json" 2>"$tmp/err"
check "repair exits 0" $?
python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
assert abs(d['volume'] - (0.505952 - 0.259048)) < 2e-6, d['volume']
assert d['mesh']['shells'][1]['inside_of'] == 0
assert 'cavities inward' in d['repair']
" "$tmp/hs.json"; check "repaired hollow sphere" $?
"$bin" "$data/meshes/blobby-shuffled.off" >"$tmp/out" 2>"$tmp/err"
grep -q "inconsistent orientation: 3069 edges.*try --repair" "$tmp/err"; check "suggests --repair" $?

# Thin shells: an open box (no top) in mm at 2.7 kg/m^2; area 5·(100 mm)^2 = 0.05 m^2.
printf 'v 0 0 0\nv 100 0 0\nv 100 100 0\nv 0 100 0\nv 0 0 100\nv 100 0 100\nv 100 100 100\nv 0 100 100\nf 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n' >"$tmp/tray.obj"
"$bin" "$tmp/tray.obj" --unit mm >/dev/null 2>"$tmp/err"
[ $? -eq 1 ]; check "open tray refused as a solid" $?
"$bin" "$tmp/tray.obj" --unit mm --shell --area-density 2.7 --format json >"$tmp/shell.json" 2>"$tmp/err"
check "open tray accepted as a shell" $?
python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
assert d['model'] == 'shell' and d['density'] is None and d['area_density'] == 2.7, d
assert abs(d['surface_area'] - 0.05) < 1e-15 and abs(d['mass'] - 0.135) < 1e-15, d
# COM: bottom at z = 0 (1/5 of the area), four sides at z = 0.05 -> z = 0.04
assert max(abs(a - b) for a, b in zip(d['center_of_mass'], (0.05, 0.05, 0.04))) < 1e-15, d['center_of_mass']
" "$tmp/shell.json"; check "shell JSON: area, mass, COM" $?
"$bin" "$tmp/tray.obj" --shell >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "needs --area-density" "$tmp/err"; check "--shell without a density" $?

# Walls: the cube of cube_cup_quad is not needed; Spot with a 5 mm wall, and a wall too thick.
"$bin" "$data/meshes/spot.obj" --wall 0.005 --format json >"$tmp/wall.json" 2>"$tmp/err"
check "spot with a 5 mm wall" $?
python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
assert d['model'] == 'wall' and d['wall_thickness_m'] == 0.005
# thin-wall estimate: area x t = 0.0285, less the curvature of the inner surface
assert 0.027 < d['volume'] < 0.0286, d['volume']
" "$tmp/wall.json"; check "wall volume near area x thickness" $?
"$bin" "$data/meshes/spot.obj" --wall 0.2 >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "wall of 0.2 is thicker than the part allows" "$tmp/err"; check "wall too thick refused" $?
"$bin" "$tmp/tray.obj" --wall 1 >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "A wall needs a closed surface" "$tmp/err"; check "wall of an open mesh refused" $?

# Monte Carlo: --implicit with error bars that cover the closed form; --winding-number on an open mesh.
"$bin" --implicit 'torus(R=1, r=0.25)' --qmc --samples 1e6 --density 2 --format json -q >"$tmp/torus.json" 2>"$tmp/err"
check "--implicit torus exits 0" $?
python3 -c "
import json, math, sys
d = json.load(open(sys.argv[1]))
e = d['estimate']
assert d['model'] == 'implicit' and e['method'] == 'quasi-monte-carlo' and e['randomizations'] == 16, e
v = 2 * math.pi ** 2 * 0.0625
se = e['standard_errors']
assert abs(d['volume'] - v) < 4.5 * se['volume'], (d['volume'], v, se['volume'])
assert abs(d['mass'] - 2 * v) < 4.5 * se['mass']
assert 0 < se['volume'] < 1e-3 * v
izz = 2 * v * (1 + 0.75 * 0.0625)
assert abs(d['principal_moments'][2] - izz) < 4.5 * se['principal_moments'][2], (d['principal_moments'], izz)
" "$tmp/torus.json"; check "--implicit torus within its error bars" $?
"$bin" --implicit 'torus(R=1, r=2)' >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "r must be smaller than R" "$tmp/err"; check "--implicit bad shape message" $?
"$bin" --implicit 'box(x=1, y=2, z=3)' --mc --samples 200000 --seed 7 -q >"$tmp/a" 2>/dev/null
"$bin" --implicit 'box(x=1, y=2, z=3)' --mc --samples 200000 --seed 7 -q --threads 1 >"$tmp/b" 2>/dev/null
diff <(grep -v integration "$tmp/a") <(grep -v integration "$tmp/b") >/dev/null; check "same seed, same output, any thread count" $?
"$bin" "$tmp/tray.obj" --unit mm --winding-number --tolerance 3e-3 --format json -q >"$tmp/wn.json" 2>"$tmp/err"
check "--winding-number accepts an open mesh" $?
grep -q "the winding number bridges the holes" "$tmp/err"; check "--winding-number says it bridged the holes" $?
python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
se = d['estimate']['standard_errors']
# the open tray is read as the closed 0.1 m cube: 1e-3 m^3
assert abs(d['volume'] - 1e-3) < 4.5 * se['volume'], (d['volume'], se['volume'])
assert d['estimate']['tolerance_met']
" "$tmp/wn.json"; check "--winding-number closes the open tray into the cube" $?
"$bin" "$data/meshes/spot.obj" --implicit 'sphere(r=1)' --samples 4096 --format csv -q >"$tmp/mc.csv" 2>/dev/null
python3 -c "
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2 and rows[0]['se_mass'] == '' and float(rows[1]['se_mass']) > 0, rows
" "$tmp/mc.csv"; check "CSV: standard-error columns for the estimate, empty for the exact row" $?
"$bin" "$data/meshes/spot.obj" --samples 1000 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "belong to --implicit or --winding-number" "$tmp/err"; check "sampling flags without a sampling path" $?

# Argument conventions shared by both commands: exit 2 for every argument error, --version,
# reserved subcommand words.
"$bin" "$data/meshes/spot.obj" --unit furlong >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "unit" "$tmp/err"; check "unknown unit exits 2" $?
"$bin" "$data/meshes/spot.obj" --no-such-option >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "unknown option exits 2" $?
"$bin" "$data/meshes/spot.obj" --density -3 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "negative density exits 2" $?
"$bin" --version >"$tmp/out" 2>&1
[ $? -eq 0 ] && grep -Eq "^massprops [0-9]+\.[0-9]+\.[0-9]+$" "$tmp/out"; check "--version" $?

# Assemblies: --parts and --density-map (values against closed forms: tests/massprops/parts_test.cpp).
"$bin" "$data/meshes/assembly_bracket.obj" --parts --format json -q >"$tmp/parts.json" 2>"$tmp/err"
check "--parts exits 0" $?
python3 - "$tmp/parts.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert [p["part"] for p in d["parts"]] == ["base", "post", "insert_brass"], d["parts"]
assert abs(sum(p["mass"] for p in d["parts"]) - d["mass"]) < 1e-15
assert "part" not in d and all("parts" not in p for p in d["parts"])
PY
check "--parts JSON: a parts array whose masses add up" $?
"$bin" "$data/meshes/assembly_bracket.obj" --parts --format csv -q >"$tmp/parts.csv" 2>"$tmp/err"
[ "$(wc -l <"$tmp/parts.csv")" -eq 5 ] && head -1 "$tmp/parts.csv" | grep -q "^file,part,unit," &&
  grep -q '"insert_brass"' "$tmp/parts.csv"; check "--parts CSV: a row per part and one for the whole" $?
printf 'part,density,mass\nbase,2700,\npost,7850,\n"insert_*",,0.017\n' >"$tmp/map.csv"
"$bin" "$data/meshes/assembly_bracket.obj" --density-map "$tmp/map.csv" --format json -q >"$tmp/csvmap.json" 2>"$tmp/err"
check "--density-map CSV exits 0" $?
"$bin" "$data/meshes/assembly_bracket.obj" --density-map "$data/meshes/assembly_bracket_materials.json" \
  --format json -q >"$tmp/jsonmap.json" 2>"$tmp/err"
check "--density-map JSON exits 0" $?
python3 - "$tmp/csvmap.json" "$tmp/jsonmap.json" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
assert a["mass"] == b["mass"] and a["inertia_com"] == b["inertia_com"]
assert abs(a["mass"] - (2700 * 6e-5 + 7850 * 3.2e-5 + 0.017)) < 1e-12, a["mass"]
PY
check "--density-map: the CSV and JSON maps give the same whole" $?
echo '{"bse": 2700}' >"$tmp/typo.json"
"$bin" "$data/meshes/assembly_bracket.obj" --density-map "$tmp/typo.json" -q >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "'bse' matches no part" "$tmp/err"; check "--density-map entry matching no part is an error" $?
echo '{"base": "dense"}' >"$tmp/bad.json"
"$bin" "$data/meshes/assembly_bracket.obj" --density-map "$tmp/bad.json" -q >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "entry 'base'" "$tmp/err"; check "malformed --density-map exits 2" $?
"$bin" "$data/meshes/assembly_bracket.obj" --parts --shell --area-density 1 -q >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "--parts with --shell exits 2" $?

# Robot descriptions: massprops fill (values: tests/robot/fill_test.cpp; consumers:
# tests/robot/consumers_test.py).
"$bin" fill "$data/robots/demo_arm.urdf" -o "$tmp/arm.urdf" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 0 ] && grep -q "5 filled, 0 failed, 0 without geometry" "$tmp/out" && [ "$(grep -c "<inertial>" "$tmp/arm.urdf")" -eq 5 ]
check "fill a URDF" $?
"$bin" fill "$data/robots/demo_arm.urdf" >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "fill without -o exits 2" $?
"$bin" fill "$data/robots/demo_arm.urdf" -o "$data/robots/demo_arm.urdf" >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "fill refuses to overwrite its input" $?
"$bin" fill "$data/robots/demo_arm.urdf" -o "$tmp/x.urdf" --package nodir >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "NAME=DIR" "$tmp/err"; check "fill --package without = exits 2" $?
printf '<robot name="r">\n  <link name="a"><collision><geometry><mesh filename="gone.stl"/></geometry></collision></link>\n  <link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>\n</robot>\n' >"$tmp/r.urdf"
"$bin" fill "$tmp/r.urdf" -o "$tmp/r_out.urdf" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "link 'a'.*gone.stl" "$tmp/err" && [ "$(grep -c "<inertial>" "$tmp/r_out.urdf")" -eq 1 ]
check "fill: a link that fails is named, the others are filled, exit 1" $?
"$bin" fill "$data/meshes/spot.obj" -o "$tmp/x.urdf" >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "not well-formed XML" "$tmp/err"; check "fill of a non-XML file exits 1" $?
# Output files: never over a device node or an input.
"$bin" "$data/meshes/t_handle.obj" -o /dev/null >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "not a regular file" "$tmp/err" && [ -c /dev/null ]; check "-o /dev/null refused" $?
cp "$data/meshes/t_handle.obj" "$tmp/in.obj"
"$bin" "$tmp/in.obj" -o "$tmp/in.obj" >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "is also an input" "$tmp/err" && cmp -s "$tmp/in.obj" "$data/meshes/t_handle.obj"; check "-o naming an input refused" $?
mkfifo "$tmp/fifo.obj"
timeout 10 "$bin" "$tmp/fifo.obj" >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "not a regular file" "$tmp/err"; check "a FIFO as input is refused, not waited on" $?
"$bin" --implicit 'sphere(r=1)' --shell --area-density 1 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "--implicit with --shell refused" $?
"$bin" --implicit 'sphere(r=1)' --repair >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "--implicit alone with a mesh option refused" $?
"$bin" "$data/meshes/spot.obj" --density nan >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "finite" "$tmp/err"; check "--density nan refused" $?
"$bin" "$data/meshes/spot.obj" --threads -1 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && ! grep -q "[0-9]\{30\}" "$tmp/err"; check "range messages without 309 digits" $?

# Several files are computed side by side; what is printed (results, warnings, errors, their
# order) is the same bytes as one at a time.
many=("$data"/meshes/*.obj "$data"/meshes/*.stl "$data"/meshes/*.STL "$data"/meshes/*.off "$tmp/open.obj")
"$bin" "${many[@]}" --format json --threads 1 >"$tmp/one.json" 2>"$tmp/one.err"; one=$?
"$bin" "${many[@]}" --format json --threads 4 >"$tmp/four.json" 2>"$tmp/four.err"; four=$?
[ $one -eq 1 ] && [ $four -eq 1 ] && cmp -s "$tmp/one.json" "$tmp/four.json" && cmp -s "$tmp/one.err" "$tmp/four.err" &&
  grep -q "open.obj" "$tmp/four.err"; check "several files: same output whatever the threads" $?

# Report frames and units: the T-handle (56 g at density 1000, its center of mass at y = −1/140 m)
# in g, mm, g*mm^2, about the crossbar's top (0, 0.02, 0) m, turned by 90° about z.
"$bin" "$data/meshes/t_handle.obj" --unit m --output-units mmgs --about 0,0.02,0 --axes-euler 90,0,0 \
  --format json -q >"$tmp/mmgs.json"
[ $? -eq 0 ]; check "--output-units/--about/--axes-euler run" $?
"$bin" "$data/meshes/t_handle.obj" --unit m --format json -q >"$tmp/si.json"
/usr/bin/python3 - "$tmp/mmgs.json" "$tmp/si.json" <<'PY'
import json, sys
g, si = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
close = lambda a, b, rel=1e-14: abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)
assert g["units"] == {"mass": "g", "length": "mm", "area": "mm^2", "volume": "mm^3", "density": "g/mm^3",
                      "inertia": "g*mm^2"}, g["units"]
assert si["units"]["inertia"] == "kg*m^2"
assert close(g["mass"], si["mass"] * 1e3) and close(g["volume"], si["volume"] * 1e9)
assert close(g["center_of_mass"][1], si["center_of_mass"][1] * 1e3)
assert all(close(a, b * 1e9) for a, b in zip(g["principal_moments"], si["principal_moments"]))
# About (0, 20 mm, 0): d = 20 + 1000/140 mm along y; in the turned axes x' = y, y' = −x.
m, d = 56.0, 20 + 1000 / 140
t = g["inertia_about"]["tensor"]
ic = si["inertia_com"]
assert g["inertia_about"]["point"] == [0, 20, 0]
assert close(t[0][0], ic[1][1] * 1e9, 1e-12)                 # about y: no shift along y
assert close(t[1][1], ic[0][0] * 1e9 + m * d * d, 1e-12)     # about x: + m d²
assert close(t[2][2], ic[2][2] * 1e9 + m * d * d, 1e-12)
PY
check "units and frames agree with SI and the parallel-axis theorem" $?
"$bin" "$data/meshes/t_handle.obj" --output-units ips --format csv -q | head -1 | grep -q "volume_in3,mass_lb,density_lb_in3,com_x_in" && \
  "$bin" "$data/meshes/t_handle.obj" --output-units ips --format csv -q | head -1 | grep -q "ixx_lb_in2"
check "CSV columns named by their units" $?
"$bin" "$data/meshes/t_handle.obj" --output-units g,mm >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "si, mmgs, cgs or ips" "$tmp/err"; check "bad --output-units exits 2" $?
"$bin" "$data/meshes/t_handle.obj" --axes 1,0,0,0,1,0,0,0,2 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "not orthonormal" "$tmp/err"; check "--axes that are no rotation exit 2" $?
"$bin" "$data/meshes/t_handle.obj" --about 0,0,0 --format urdf >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "URDF, SDF and MJCF" "$tmp/err"; check "--about with URDF exits 2" $?

# The convex hull beside the exact numbers: the T-handle's hull is a hexagonal prism, 9.2e-5 m^3.
"$bin" "$data/meshes/t_handle.obj" --unit m --hull --format json -q | \
  /usr/bin/python3 -c "import json, sys; h = json.load(sys.stdin)['hull']; assert abs(h['volume'] - 9.2e-5) < 1e-18, h"
check "--hull in JSON" $?
"$bin" "$data/meshes/t_handle.obj" --hull --shell --area-density 1 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "--hull with --shell exits 2" $?

# --exact: certified numbers, with the default path's difference.
"$bin" "$data/meshes/t_handle.obj" --unit m --exact --format json -q | /usr/bin/python3 -c "
import json, sys
d = json.load(sys.stdin)
e = d['exact']
assert e['certified'] and e['default_path_inertia_difference'] < 1e-12, e
assert all(lo <= m <= hi for (lo, hi), m in zip(e['principal_moments_enclosure'], d['principal_moments'])), e
assert d['volume'] == 5.6e-05 and d['mass'] == 0.056
"
check "--exact in JSON" $?
"$bin" "$data/meshes/t_handle.obj" --exact --wall 0.001 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "--exact with --wall exits 2" $?

# massprops validate: the convergence table, as JSON, and its plot.
"$bin" validate --solids box,torus --resolutions 16,32 --format json --plot "$tmp/conv.png" >"$tmp/val.json"
[ $? -eq 0 ] && head -c 8 "$tmp/conv.png" | od -c | grep -q "P   N   G" && /usr/bin/python3 -c "
import json; rows = json.load(open('$tmp/val.json'))
assert {r['solid'] for r in rows} == {'box', 'torus'} and len(rows) == 4 + 8
assert all(abs(r['inertia_order'] - 2) < 0.1 for r in rows if r['resolution'] == 32)
"
check "validate: JSON rows and a PNG" $?
"$bin" validate --solids dodecahedron >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "unknown solid" "$tmp/err"; check "validate: unknown solid exits 2" $?

# Advice in messages is worded in the command line's vocabulary.
"$bin" "$tmp/open.obj" >/dev/null 2>"$tmp/err"
grep -q "try --repair (it fills holes.*--winding-number for an estimate with error bars, or pass --allow-open" "$tmp/err"; check "CLI vocabulary in errors" $?

# Pictures: SVG and PNG by the extension, written whole; an unknown extension, several inputs and
# a folder as the output are refused before anything is computed.
"$bin" "$data/meshes/t_handle.obj" --picture "$tmp/t.svg" -q >/dev/null && grep -q "<g id='view-isometric'" "$tmp/t.svg"
check "--picture writes the SVG" $?
"$bin" "$data/meshes/Moon.stl" --parts --picture "$tmp/m.png" -q >/dev/null && [ "$(head -c 4 "$tmp/m.png" | tail -c 3)" = PNG ]
check "--picture writes a PNG (a binary STL, read whole)" $?
"$bin" --implicit 'sphere(r=1)' --samples 1e4 --picture "$tmp/s.svg" -q >/dev/null && [ "$(grep -c '<polygon points' "$tmp/s.svg")" -gt 1000 ] &&
  grep -q ">≈ 2 m</text>" "$tmp/s.svg"
check "--picture of an implicit solid draws its surface and its 2 m box" $?
# The box of a polygonized surface is approximate: marked so, and within the cell it names of the
# solid's own (a box turned 30° about z: 0.3 cos 30° + 0.2 sin 30° by 0.3 sin 30° + 0.2 cos 30°).
"$bin" --implicit 'rotate(box(x=0.3,y=0.2,z=0.1), axis=[0,0,1], deg=30)' --samples 1e4 --picture "$tmp/rb.svg" -q >/dev/null
/usr/bin/python3 - "$tmp/rb.svg" <<'PY'
import math, re, sys
svg = open(sys.argv[1], encoding="utf-8").read()
cell = float(re.search(r"of the surface drawn, within about ([0-9.e+-]+) m of the solid", svg).group(1))
dims = {k: float(v) for k, v in re.findall(r">([xyz]) ≈ ([0-9.e+-]+) m<", svg)}
c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
truth = {"x": 0.3 * c + 0.2 * s, "y": 0.3 * s + 0.2 * c, "z": 0.1}
assert set(dims) == set("xyz"), dims
for k in "xyz":
    assert abs(dims[k] - truth[k]) <= cell + 1e-4 * truth[k], (k, dims[k], truth[k], cell)
PY
check "--picture of an implicit solid marks its box approximate, within a cell" $?
# An estimate's legend carries its error bars; repeated moments are said to leave the axes a choice
# (a torus: I1 = I2 within the error bars; a cube: all three, exactly).
"$bin" --implicit 'torus(R=1, r=0.25)' --samples 1e4 --picture "$tmp/tor.svg" -q >/dev/null 2>&1 &&
  grep -q "mass [0-9.e+-]* ± [0-9.e+-]* kg" "$tmp/tor.svg" && grep -q "± one standard error" "$tmp/tor.svg" &&
  grep -q "principal moments 1 and 2 are equal within their error bars" "$tmp/tor.svg"
check "--picture of an estimate: error bars and the undetermined axes" $?
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n' >"$tmp/cube.obj"
"$bin" "$tmp/cube.obj" --picture "$tmp/cube.svg" -q >/dev/null && grep -q "the three principal moments are equal:" "$tmp/cube.svg" &&
  ! grep -q "±" "$tmp/cube.svg"
check "--picture of a cube: every axis principal, no error bars" $?
"$bin" "$data/meshes/t_handle.obj" --picture "$tmp/t.jpg" -q >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "a picture is .svg or .png" "$tmp/err" && [ ! -e "$tmp/t.jpg" ]; check "--picture .jpg refused" $?
"$bin" "$data/meshes/t_handle.obj" "$data/meshes/spot.obj" --picture "$tmp/two.svg" -q >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "draws one input" "$tmp/err"; check "--picture with two inputs refused" $?
"$bin" "$data/meshes/t_handle.obj" --picture "$tmp" -q >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "--picture to a folder refused" $?

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
