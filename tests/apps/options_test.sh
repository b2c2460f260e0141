#!/usr/bin/env bash
# The load options are declared once (massprops/io/load_schema.h): every command that takes one
# refuses a bad value in the same words and with exit status 2, the Python module in the same
# words as a ValueError, and a scene names its field with the same rule.
# Usage: options_test.sh MASSPROPS RBSIM DATA_DIR PYTHONPATH
set -u
massprops=$1
rbsim=$2
data=$3
pythonpath=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
passes=0
check() {  # check NAME EXIT-CODE-OF-THE-CONDITION
  if [ "$2" -eq 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
mesh="$data/meshes/t_handle.obj"
printf '<robot name="r"><link name="a"/></robot>\n' >"$tmp/r.urdf"

# refused COMMAND... -- EXPECTED: exit status 2 and EXPECTED on stderr.
refused() {
  local args=() expected
  while [ "$1" != "--" ]; do args+=("$1"); shift; done
  expected=$2
  "${args[@]}" >/dev/null 2>"$tmp/err"
  local status=$?
  [ $status -eq 2 ] && grep -qF -- "$expected" "$tmp/err"
  check "${args[*]}: exit 2 (got $status) and '$expected' ($(head -c 200 "$tmp/err"))" $?
}

threads="--threads: must be between 0 and 4096, got -1"
refused "$massprops" "$mesh" --threads -1 -- "$threads"
refused "$massprops" batch "$data/meshes" -o "$tmp/o.jsonl" --threads -1 -- "$threads"
refused "$massprops" fill "$tmp/r.urdf" -o "$tmp/f.urdf" --threads -1 -- "$threads"
refused "$rbsim" "$data/scenes/t_handle.json" --threads -1 -- "$threads"
refused "$rbsim" poses "$mesh" --threads -1 -- "$threads"
unit="--unit: must be m, cm, mm, in, ft or um, got 'furlong'"
refused "$massprops" "$mesh" --unit furlong -- "$unit"
refused "$rbsim" --mesh "$mesh" --unit furlong -- "$unit"
refused "$rbsim" poses "$mesh" --unit furlong -- "$unit"
density="--density: must be > 0, got -3"
refused "$massprops" "$mesh" --density -3 -- "$density"
refused "$rbsim" --mesh "$mesh" --density -3 -- "$density"
refused "$rbsim" poses "$mesh" --density -3 -- "$density"
refused "$massprops" "$mesh" --density nan -- "--density: must be a finite number, got nan"

# The Python module: the same rule after the keyword's name.
PYTHONPATH="$pythonpath" /usr/bin/python3 - "$mesh" >"$tmp/py" 2>&1 <<'PY'
import sys
import massprops
for kw, expected in [({"threads": -1}, "threads must be between 0 and 4096, got -1"),
                     ({"unit": "furlong"}, "unit must be m, cm, mm, in, ft or um, got 'furlong'"),
                     ({"density": -3}, "density must be > 0, got -3"),
                     ({"density": 1000, "mass": 2}, "give density or mass, not both")]:
    try:
        massprops.load(sys.argv[1], **kw)
        print("accepted", kw)
    except ValueError as e:
        print("ok" if expected in str(e) else f"wrong message for {kw}: {e}")
PY
[ "$(grep -c "^ok$" "$tmp/py")" -eq 4 ]; check "python: the same words ($(cat "$tmp/py"))" $?

# A scene: the field named, the same rule.
printf '{"bodies": [{"mesh": "%s", "unit": "furlong"}], "duration": 0.01}' "$mesh" >"$tmp/s.json"
"$rbsim" "$tmp/s.json" >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] && grep -qF "bodies[0].unit: must be m, cm, mm, in, ft or um, got 'furlong'" "$tmp/err"
check "scene: the field and the same rule ($(cat "$tmp/err"))" $?

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
