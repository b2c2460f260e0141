#!/usr/bin/env bash
# End-to-end checks of the rbsim command: outputs of an example scene (CSV columns, JSON lines,
# plot files, the .glb through the Khronos glTF validator), the quick path, scene errors and an
# interrupted run.
# Usage: rbsim_cli_test.sh RBSIM_BINARY DATA_DIR VALIDATOR_DIR
set -u
bin=$1
data=$2
validator=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
passes=0

check() {  # check NAME EXIT-CODE-OF-THE-CONDITION
  if [ "$2" -eq 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
glb_json() {  # glb_json FILE.glb: the JSON chunk of a binary glTF (its header is 12 bytes, the chunk's 8)
  python3 -c 'import struct, sys; b = open(sys.argv[1], "rb").read(); n = struct.unpack_from("<I", b, 12)[0]
sys.stdout.write(b[20:20 + n].decode())' "$1"
}

# 1. The T-handle example, 3 s: every output, whole, with the documented columns.
"$bin" "$data/scenes/t_handle.json" --duration 3 --out "$tmp/t" --outputs csv,jsonl,diagnostics,svg,png,glb \
  >"$tmp/out" 2>"$tmp/err"
check "t_handle exits 0" $?
grep -q "energy, J" "$tmp/out"; check "summary printed" $?
grep -q "conserved by this scene's physics" "$tmp/out"; check "summary says what is conserved" $?
for f in trajectory.csv trajectory.jsonl diagnostics.csv plot.svg plot.png animation.glb; do
  test -s "$tmp/t/$f"; check "$f written and non-empty" $?
done
[ -z "$(ls "$tmp/t" | grep tmp-)" ]; check "no temporary files left" $?
head -c 8 "$tmp/t/plot.png" | od -An -tx1 | grep -q "89 50 4e 47 0d 0a 1a 0a"; check "plot.png is a PNG" $?
grep -q "<svg" "$tmp/t/plot.svg" && grep -q "<path" "$tmp/t/plot.svg"; check "plot.svg is an SVG with curves" $?
python3 - "$tmp/t" <<'PY'
import csv, json, math, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(d + "/trajectory.csv")))
cols = "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,w1,w2,w3".split(",")
assert list(rows[0].keys()) == cols, rows[0].keys()
# dt = 1 ms, 60 Hz -> every 17 steps; 3000 steps -> 177 + 1 + the last one
assert len(rows) == 3000 // 17 + 2, len(rows)
assert rows[0]["time"] == "0" and abs(float(rows[-1]["time"]) - 3) < 1e-12
for r in rows:
    q = [float(r[k]) for k in ("qw", "qx", "qy", "qz")]
    assert abs(math.sqrt(sum(c * c for c in q)) - 1) < 1e-12
# the initial spin is the scene's: (10, 0.01, 0.01) rad/s in the mesh axes = world axes at t = 0
w = [float(rows[0][k]) for k in ("wx", "wy", "wz")]
assert max(abs(a - b) for a, b in zip(w, (10, 0.01, 0.01))) < 1e-12, w
lines = [json.loads(l) for l in open(d + "/trajectory.jsonl")]
assert len(lines) == len(rows)
assert set(lines[0]) == {"time", "body", "position", "quaternion", "velocity", "omega", "omega_principal"}
assert all(abs(float(rows[i]["w2"]) - lines[i]["omega_principal"][1]) == 0 for i in range(len(rows)))
diag = list(csv.DictReader(open(d + "/diagnostics.csv")))
assert len(diag) == len(rows) and "energy_drift" in diag[0]
assert max(abs(float(r["energy_drift"])) for r in diag) < 1e-12
PY
check "CSV columns, row count, JSON lines, diagnostics" $?
rows=$(($(wc -l <"$tmp/t/trajectory.csv") - 1))
node "$validator/validate_glb.mjs" "$tmp/t/animation.glb" "$rows" 1 >"$tmp/val" 2>&1
check "glTF validator: no errors, one key per output step" $?
grep -q " 0 errors" "$tmp/val" || cat "$tmp/val"

# 1b. A robot with visual geometry: each link's node draws its visual, with its collider as a
# see-through child node; the validator finds no error.
"$bin" "$data/../tests/robot/field/arm_on_world.urdf" --duration 0.5 --out "$tmp/arm" --outputs csv,glb -q \
  >/dev/null 2>"$tmp/arm_err"
check "arm_on_world exits 0" $?
grep -q "link 'base_link': visual geometry not drawn" "$tmp/arm_err"; check "a missing visual mesh is a warning" $?
rows=$(($(wc -l <"$tmp/arm/trajectory.csv") - 1))
node "$validator/validate_glb.mjs" "$tmp/arm/animation.glb" "$((rows / 2))" 2 >"$tmp/val" 2>&1
check "glTF validator on a robot with visuals and colliders" $?
glb_json "$tmp/arm/animation.glb" >"$tmp/arm.json"
python3 - "$tmp/arm.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
names = [node.get("name") for node in doc["nodes"]]
arm = names.index("arm_on_world/upper_arm")
child = doc["nodes"][arm]["children"][0]
assert names[child] == "arm_on_world/upper_arm collider", names
blend = [m for m in doc["materials"] if m.get("alphaMode") == "BLEND"]
assert len(blend) == 2, doc["materials"]
PY
check ".glb: visuals drawn, colliders as see-through child nodes" $?

# 2. Two bodies: one node per body in the .glb, both animated.
"$bin" "$data/scenes/two_bodies.json" --duration 2 --out "$tmp/two" --outputs csv,glb -q >/dev/null 2>&1
check "two_bodies exits 0" $?
rows=$(( ($(wc -l <"$tmp/two/trajectory.csv") - 1) / 2 ))
node "$validator/validate_glb.mjs" "$tmp/two/animation.glb" "$rows" 2 >"$tmp/val2" 2>&1
check "two bodies: glb valid with 2 animated nodes" $?

# 2b. Contact: a static table and Spot's hull; the .glb carries the table (fixed) beside the
# animated body, the summary the contact line; the dominoes' ground becomes checkerboard nodes.
"$bin" "$data/scenes/spot_on_table.json" --duration 0.3 --out "$tmp/spot" --outputs csv,glb >"$tmp/spot.out" 2>&1
check "spot_on_table exits 0" $?
grep -q "contact: up to" "$tmp/spot.out"; check "contact summary line" $?
rows=$(($(wc -l <"$tmp/spot/trajectory.csv") - 1))
node "$validator/validate_glb.mjs" "$tmp/spot/animation.glb" "$rows" 1 >"$tmp/val3" 2>&1
check "contact scene: glb valid, the table fixed beside the animated body" $?
glb_json "$tmp/spot/animation.glb" >"$tmp/spot.json"
python3 - "$tmp/spot.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
names = [node.get("name") for node in doc["nodes"]]
assert "table" in names and "spot" in names, names
PY
check "contact scene: the .glb has the table node" $?

# 3. The quick path: one mesh, torque-free, from the command line.
"$bin" --mesh "$data/meshes/spot.obj" --omega 0,10,0.01 --duration 1 --out "$tmp/q" --outputs csv >"$tmp/out" 2>&1
check "quick path exits 0" $?
grep -q "1 body" "$tmp/out"; check "quick path summary" $?
test -s "$tmp/q/trajectory.csv"; check "quick path trajectory" $?

# 4. Errors: a clear line naming the field, exit 1, nothing written.
printf '{"bodies": [{"mesh": "missing.stl"}]}' >"$tmp/bad1.json"
"$bin" "$tmp/bad1.json" --out "$tmp/bad" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ]; check "missing mesh exits 1" $?
grep -q "bad1.json: bodies\[0\].mesh: 'missing.stl' not found" "$tmp/err"; check "missing mesh message" $?
[ ! -e "$tmp/bad" ]; check "nothing written for a bad scene" $?
printf '{"bodies": [{"solid": {"type": "sphere", "radius": 1}, "mass": -1}]}' >"$tmp/bad2.json"
"$bin" "$tmp/bad2.json" >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "bodies\[0\].mass: must be > 0, got -1" "$tmp/err"; check "negative mass" $?
printf '{"bodies": [{"solid": {"type": "sphere", "radius": 1}, "orientation": [2, 0, 0, 0]}], "duration": 0.01}' >"$tmp/q.json"
"$bin" "$tmp/q.json" >/dev/null 2>"$tmp/err"
[ $? -eq 0 ] && grep -q "warning: .*orientation: the quaternion has norm 2; normalized" "$tmp/err"; check "non-unit quaternion warning" $?
"$bin" --mesh "$data/meshes/spot.obj" --omega 1,2 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "\-\-omega: expected three finite numbers" "$tmp/err"; check "bad --omega" $?
"$bin" "$data/scenes/t_handle.json" --integrator rk5 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "\-\-integrator" "$tmp/err"; check "bad --integrator" $?

# Argument conventions: exit 2, --version, the reserved word.
"$bin" --version >"$tmp/out" 2>&1
[ $? -eq 0 ] && grep -Eq "^rbsim [0-9]+\.[0-9]+\.[0-9]+$" "$tmp/out"; check "rbsim --version" $?
# rbsim poses: the estimates, the same bits on 1 and 2 threads, pictures, argument errors.
"$bin" poses >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "poses without a part exits 2" $?
"$bin" poses "$data/meshes/t_handle.obj" --drops 120 --format json --threads 1 >"$tmp/p1.json" 2>"$tmp/err"
check "poses t_handle exits 0" $?
"$bin" poses "$data/meshes/t_handle.obj" --drops 120 --format json --threads 2 --out "$tmp/poses" >"$tmp/p2.json" \
  2>"$tmp/err"
/usr/bin/python3 - "$tmp/p1.json" "$tmp/p2.json" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
for p in b["poses"]:
    p.pop("picture")
sys.exit(0 if a == b else 1)
PY
check "poses: same table on 1 and 2 threads" $?
/usr/bin/python3 - "$tmp/p1.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
poses = j["poses"]
assert abs(sum(p["quasi_static"] for p in poses) - 1) < 1e-12
d = j["drops"]
assert sum(p["drop_count"] for p in poses) + d["not_settled"] + d["other_face"] == d["count"] == 120
for p in poses:
    lo, hi = p["drops_interval95"]
    slo, shi = p["drops_simultaneous95"]
    assert slo <= lo <= p["drops"] <= hi <= shi
    n, t = p["normal"], p["transform"]
    down = [sum(t[r][c] * n[c] for c in range(3)) for r in range(3)]
    assert abs(down[2] + 1) < 1e-12, down  # the face's normal turned straight down
PY
check "poses: probabilities, intervals and rest transforms consistent" $?
test -s "$tmp/poses/pose_1.svg" && test -s "$tmp/poses/poses.json" && grep -q "<polygon" "$tmp/poses/pose_1.svg"
check "poses --out writes pictures and poses.json" $?
"$bin" poses "$data/meshes/t_handle.obj" --ground 0.5,0.6,0 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q -- "--ground: the kinetic_friction must not exceed static_friction (0.5)" "$tmp/err"; check "poses: bad --ground exits 2" $?
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n' >"$tmp/open.obj"
"$bin" poses "$tmp/open.obj" >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "open.obj" "$tmp/err" && grep -q -- "try --repair" "$tmp/err" && ! grep -q "LoadOptions" "$tmp/err"
check "poses: open mesh refused naming the file, advice in the command's words" $?
"$bin" "$data/scenes/t_handle.json" --dt -1 >/dev/null 2>"$tmp/err"
[ $? -eq 2 ]; check "negative --dt exits 2" $?
for opt in --duration --rate --dt; do
  "$bin" "$data/scenes/t_handle.json" $opt nan >/dev/null 2>"$tmp/err"
  [ $? -eq 2 ] && grep -q "finite" "$tmp/err"; check "$opt nan refused" $?
done
# A run whose state stops being finite stops with "diverged", exit 1, and writes nothing.
cat >"$tmp/stiff.json" <<'JSON'
{"dt": 0.01, "duration": 5, "integrator": "explicit-euler",
 "bodies": [{"name": "box", "solid": {"type": "box", "size": [0.1, 0.1, 0.1]}, "position": [0, 0, -1]}],
 "forces": [{"type": "spring", "body": "box", "anchor": [0, 0, 0], "k": 1e9}]}
JSON
"$bin" "$tmp/stiff.json" --out "$tmp/stiff" -q >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "diverged at t = " "$tmp/err" && [ -z "$(ls -A "$tmp/stiff" 2>/dev/null)" ]; check "a diverging run stops, exit 1, no files" $?
"$bin" --mesh "$data/meshes/t_handle.obj" --velocity 1e300,0,0 --duration 0.01 -q >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "initial state's energy is not finite" "$tmp/err"; check "an initial state beyond double precision is refused" $?
# Scene values beyond double precision are named with the file and the field.
printf '{"bodies": [{"solid": {"type": "box", "size": [1, 1, 1]}, "density": 1e400}]}' >"$tmp/big.json"
"$bin" "$tmp/big.json" -q >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "big.json: a number is beyond double precision" "$tmp/err"; check "1e400 in a scene named" $?
printf '{"bodies": [{"solid": {"type": "sphere", "radius": 1e-200}}]}' >"$tmp/tiny.json"
"$bin" "$tmp/tiny.json" -q >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "tiny.json: bodies\[0\].solid: sphere: .*under- or overflows" "$tmp/err"; check "an underflowing solid is named with its field" $?

# A failing output (gnuplot that draws nothing) leaves no output at all, not the others.
mkdir -p "$tmp/fakebin"
printf '#!/bin/sh\ncat >/dev/null\nexit 1\n' >"$tmp/fakebin/gnuplot"
chmod +x "$tmp/fakebin/gnuplot"
PATH="$tmp/fakebin:$PATH" "$bin" "$data/scenes/t_handle.json" --duration 0.1 --out "$tmp/failing" -q >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "no output files were written" "$tmp/err" && [ -z "$(ls -A "$tmp/failing")" ]
check "a failing plot leaves no output files ($(ls -A "$tmp/failing" | tr '\n' ' '))" $?
mkfifo "$tmp/scene.json"
timeout 10 "$bin" "$tmp/scene.json" >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "not a regular file" "$tmp/err"; check "a FIFO as scene is refused, not waited on" $?

# 5. Interrupted: SIGINT mid-run leaves no file under a final name, and no temporary file.
"$bin" "$data/scenes/t_handle.json" --dt 1e-6 --duration 1000 --out "$tmp/int" -q >/dev/null 2>"$tmp/err" &
pid=$!
for _ in $(seq 50); do [ -n "$(ls "$tmp/int" 2>/dev/null)" ] && break; sleep 0.1; done
sleep 0.5
kill -INT "$pid"
wait "$pid"
[ $? -eq 130 ]; check "interrupted run exits 130" $?
grep -q "interrupted at t =" "$tmp/err"; check "interrupted message" $?
[ -z "$(ls -A "$tmp/int")" ]; check "interrupted run leaves no files ($(ls "$tmp/int" | tr '\n' ' '))" $?

# contacts.jsonl: one line per step, each contact naming its bodies, with a point, a unit normal,
# an impulse and a couple; the box stack's ground contacts carry its weight. run.html holds the run's data.
"$bin" "$data/scenes/box_stack.json" --duration 0.1 --out "$tmp/c" --outputs contacts,html -q >/dev/null
[ $? -eq 0 ]; check "contacts and html outputs" $?
/usr/bin/python3 - "$tmp/c" <<'PY'
import json, math, re, sys
d = sys.argv[1]
steps = [json.loads(l) for l in open(d + "/contacts.jsonl")]
assert [s["step"] for s in steps] == list(range(1, 101)), len(steps)
last = steps[-1]
ground = [c for c in last["contacts"] if c["b"] is None]
assert ground and all(c["a"] == "box0" for c in ground)
assert all(abs(math.hypot(*c["normal"]) - 1) < 1e-12 for c in last["contacts"])
assert all(len(c["torque"]) == 3 and all(math.isfinite(x) for x in c["torque"]) for c in last["contacts"])
weight = 10 * 500 * 0.1 ** 3 * 9.81 * 0.001  # ten boxes' weight over one step, N s
assert abs(sum(c["impulse"][2] for c in ground) - weight) < 1e-6 * weight, sum(c["impulse"][2] for c in ground)
page = open(d + "/run.html").read()
run = json.loads(re.search(r"<script type='application/json' id='rbsim-run'>(.*?)</script>", page, re.S).group(1))
assert [b["name"] for b in run["bodies"]] == [f"box{i}" for i in range(10)]
assert len(run["times"]) == len(run["contacts"]) and run["force_scale"] > 0
PY
check "contacts.jsonl carries the stack's weight; run.html has the run" $?
"$bin" poses "$data/meshes/t_handle.obj" --drops 0 --format html >"$tmp/poses.html"
[ $? -eq 0 ] && grep -q "id='rbsim-run'" "$tmp/poses.html" && grep -q '"title":"t_handle.obj: resting poses"' "$tmp/poses.html"
check "rbsim poses --format html" $?

# Robot files as vendors publish them: an MJCF scene that includes its robot stands on the file's
# own floor (2 cm below z = 0, no second ground); a body whose collision bits touch nothing of the
# floor falls through it with a warning, never silently.
field="$data/../tests/robot/field"
"$bin" "$field/mjcf/scene.xml" --duration 1 -q >"$tmp/out" 2>"$tmp/err"
[ $? -eq 0 ] && grep -q '<include file="biped.xml"> followed' "$tmp/err" && ! grep -q "below the ground" "$tmp/err"
check "rbsim scene.xml: included robot on the file's floor" $?
"$bin" "$field/mjcf/masks.xml" --duration 1 -q >"$tmp/out" 2>"$tmp/err"
[ $? -eq 0 ] && grep -q "warning: body 'masks/ghost' ended the run .* m below the ground" "$tmp/err" \
  && grep -q "warning: body 'masks/ghost'" "$tmp/out" && [ "$(grep -c "below the ground" "$tmp/err")" -eq 1 ]
check "rbsim: a body through the floor is warned of" $?
"$bin" "$field/arm_on_world.urdf" --duration 0.5 -q >"$tmp/out" 2>"$tmp/err"
[ $? -eq 0 ] && grep -q "<transmission> (1)" "$tmp/err" && grep -q "bracket_repeated.stl" "$tmp/err"
check "rbsim: a vendor URDF with transmissions, a world link and a repeated-face STL runs" $?

printf '<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link><link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>' >"$tmp/massless.urdf"
"$bin" "$tmp/massless.urdf" --duration 0.01 -q >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ] && [ "$(grep -o "massless.urdf" "$tmp/err" | wc -l)" -eq 1 ] && grep -q "link 'b' has no mass" "$tmp/err"
check "rbsim: a robot's fault names its file once" $?

# ROS packages: a description whose package://acme_meshes/ is a folder of another name, found with
# --package, a scene's "packages", ROS_PACKAGE_PATH (by its package.xml) and AMENT_PREFIX_PATH.
mkdir -p "$tmp/ws/src/vendor_meshes/meshes" "$tmp/install/share/acme_meshes/meshes" "$tmp/desc"
for d in "$tmp/ws/src/vendor_meshes" "$tmp/install/share/acme_meshes"; do
  printf 'v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >"$d/meshes/link.obj"
  printf '<?xml version="1.0"?>\n<package format="2">\n  <name>acme_meshes</name>\n</package>\n' >"$d/package.xml"
done
printf '<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial><collision><geometry><mesh filename="package://acme_meshes/meshes/link.obj"/></geometry></collision></link></robot>' >"$tmp/desc/robot.urdf"
env -u ROS_PACKAGE_PATH -u AMENT_PREFIX_PATH "$bin" "$tmp/desc/robot.urdf" --duration 0.01 -q >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "the package 'acme_meshes' is not found in .*ROS_PACKAGE_PATH and AMENT_PREFIX_PATH (map it with --package acme_meshes=DIR)" "$tmp/err"
check "rbsim: an unknown package says where it looked and how to map it" $?
env -u ROS_PACKAGE_PATH -u AMENT_PREFIX_PATH "$bin" "$tmp/desc/robot.urdf" --package "acme_meshes=$tmp/ws/src/vendor_meshes" \
  --duration 0.01 -q --out "$tmp/pkg" >"$tmp/out" 2>"$tmp/err"
check "rbsim --package NAME=DIR" $?
ROS_PACKAGE_PATH="$tmp/ws/src" "$bin" "$tmp/desc/robot.urdf" --duration 0.01 -q >"$tmp/out" 2>"$tmp/err"
check "rbsim: ROS_PACKAGE_PATH searched by package.xml" $?
env -u ROS_PACKAGE_PATH AMENT_PREFIX_PATH="$tmp/install" "$bin" "$tmp/desc/robot.urdf" --duration 0.01 -q >"$tmp/out" 2>"$tmp/err"
check "rbsim: AMENT_PREFIX_PATH/share/NAME" $?
"$bin" "$tmp/desc/robot.urdf" --package acme_meshes --duration 0.01 -q >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "error: --package takes NAME=DIR, got 'acme_meshes'" "$tmp/err"
check "rbsim: --package without =DIR is a bad argument" $?
printf '{"duration": 0.01, "robots": [{"file": "desc/robot.urdf", "packages": {"acme_meshes": "ws/src/vendor_meshes"}}]}' >"$tmp/pkg_scene.json"
env -u ROS_PACKAGE_PATH -u AMENT_PREFIX_PATH "$bin" "$tmp/pkg_scene.json" -q >"$tmp/out" 2>"$tmp/err"
check "rbsim: a scene robot's \"packages\"" $?
printf '{"duration": 0.01, "robots": [{"file": "desc/robot.urdf"}]}' >"$tmp/pkg_scene2.json"
env -u ROS_PACKAGE_PATH -u AMENT_PREFIX_PATH "$bin" "$tmp/pkg_scene2.json" -q >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "robots\[0\]: .*(map it with \"packages\": {\"acme_meshes\": \"DIR\"} in the robot's entry)" "$tmp/err"
check "rbsim: a scene's unknown package is worded for scenes" $?

# rbsim PART: parts dropped until they rest; inputs told apart by content.
"$bin" "$data/meshes/t_handle.obj" -q >"$tmp/out" 2>"$tmp/err"
[ $? -eq 0 ] && grep -q "at rest at t = " "$tmp/out" && grep -qE "^  t_handle +face +\(\+0.000, \+0.000, -1.000\) +0.01 " "$tmp/out"
check "rbsim PART: dropped flat, at rest on its face 1 cm up ($(head -c 300 "$tmp/err"))" $?
"$bin" "$data/README.md" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "README.md: not a scene (.json), a robot description (URDF, SDFormat or MJCF" "$tmp/err"
check "rbsim: a file that is no scene, robot or mesh is named, exit 2" $?
printf '<?xml version="1.0"?>\n<!-- exported -->\n<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link></robot>\n' >"$tmp/robot_description.txt"
"$bin" "$tmp/robot_description.txt" --duration 0.01 -q >"$tmp/out" 2>"$tmp/err"
check "rbsim: a URDF is told by its root element, whatever its name ($(head -c 300 "$tmp/err"))" $?
"$bin" "$data/meshes/t_handle.obj" "$data/scenes/t_handle.json" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "a scene or robot file runs alone" "$tmp/err"
check "rbsim: a scene among parts is refused" $?
"$bin" "$data/scenes/t_handle.json" --count 3 >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "for parts dropped" "$tmp/err"
check "rbsim: drop flags with a scene are refused" $?
"$bin" "$data/meshes/t_handle.obj" --separate >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "give --parts too" "$tmp/err"
check "rbsim: --separate needs --parts" $?
"$bin" "$data/meshes/t_handle.obj" --orientation 1,0,0 >"$tmp/out" 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "error: --orientation: expected file, upright, random or AX,AY,AZ,DEG" "$tmp/err"
check "rbsim: a bad --orientation is named" $?
"$bin" "$data/meshes/t_handle.obj" --count 4 --orientation random --seed 5 --save-scene "$tmp/drop.json" \
  --out "$tmp/drop1" --outputs csv -q >"$tmp/out1" 2>"$tmp/err"
check "rbsim PART --save-scene --out" $?
"$bin" "$tmp/drop.json" --out "$tmp/drop2" --outputs csv -q >"$tmp/out2" 2>"$tmp/err"
check "rbsim: the saved drop runs" $?
cmp -s "$tmp/drop1/trajectory.csv" "$tmp/drop2/trajectory.csv" && cmp -s "$tmp/drop1/summary.json" "$tmp/drop2/summary.json"
check "rbsim: the saved drop gives the same trajectory and resting poses, bit for bit" $?
"$bin" "$data/meshes/ellipe0.003.off" >"$tmp/out" 2>"$tmp/err"
[ $? -eq 1 ] && grep -q "ellipe0.003.off: the signed volume is negative" "$tmp/err"
check "rbsim PART: massprops' own refusal" $?

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
