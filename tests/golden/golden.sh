#!/usr/bin/env bash
# Golden regression suite: runs every case of cases.txt (massprops) and every example scene
# (rbsim) and compares the outputs bit for bit with the recorded ones.
#   golden.sh [--update] BUILD_DIR
# Exit 0 when all match; prints a diff of the first lines that differ otherwise.
set -u
update=0
if [ "${1:-}" = "--update" ]; then update=1; shift; fi
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
massprops=$build/apps/massprops
rbsim=$build/apps/rbsim/rbsim
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$root"
passed=0
failed=0

compare() {  # compare NAME ACTUAL EXPECTED
  if [ $update -eq 1 ]; then
    mkdir -p "$(dirname "$3")"
    cp "$2" "$3"
    passed=$((passed + 1))
  elif cmp -s "$2" "$3"; then
    passed=$((passed + 1))
  else
    echo "FAIL: $1 differs from $3"
    diff "$3" "$2" | head -20
    failed=$((failed + 1))
  fi
}

while IFS='|' read -r name args; do
  name=$(echo "$name" | xargs)
  case "$name" in ''|\#*) continue ;; esac
  # shellcheck disable=SC2086
  read -r -a argv <<<"$args"
  "$massprops" "${argv[@]}" -q >"$tmp/out" 2>"$tmp/err"
  status=$?
  # The table's timing line varies from run to run; everything else must not.
  sed -i -E 's/, [0-9.e+-]+ s$/, (time) s/' "$tmp/out"
  { echo "-- stderr"; cat "$tmp/err"; echo "-- exit $status"; } >>"$tmp/out"
  compare "massprops $name" "$tmp/out" "$here/massprops/$name.out"
done <"$here/cases.txt"

# Long simulations run once, in the Release build: under the sanitizers they are skipped.
sanitized=0
grep -q '^MASSPROPS_SANITIZE:BOOL=ON' "$build/CMakeCache.txt" 2>/dev/null && sanitized=1
long_scenes=" pile_in_bin "
skipped=0

for scene in data/scenes/*.json; do
  name=$(basename "$scene" .json)
  if [ $sanitized -eq 1 ] && [[ "$long_scenes" == *" $name "* ]]; then
    skipped=$((skipped + 1))
    continue
  fi
  rm -rf "$tmp/run"
  "$rbsim" "$scene" --out "$tmp/run" --outputs csv,diagnostics -q --threads 2 >"$tmp/summary" 2>"$tmp/err"
  status=$?
  if [ $status -ne 0 ]; then
    echo "FAIL: rbsim $scene exited $status: $(cat "$tmp/err")"
    failed=$((failed + 1))
    continue
  fi
  compare "rbsim $name trajectory" "$tmp/run/trajectory.csv" "$here/rbsim/$name.trajectory.csv"
  compare "rbsim $name diagnostics" "$tmp/run/diagnostics.csv" "$here/rbsim/$name.diagnostics.csv"
  if [ -f "$tmp/run/joints.csv" ]; then
    compare "rbsim $name joints" "$tmp/run/joints.csv" "$here/rbsim/$name.joints.csv"
  fi
  if [ -f "$tmp/run/constraints.csv" ]; then
    compare "rbsim $name constraints" "$tmp/run/constraints.csv" "$here/rbsim/$name.constraints.csv"
  fi
done

# Resting poses of the example parts: both estimates, the intervals and the rest transforms.
for part in t_handle cube_cup_quad; do
  "$rbsim" poses "data/meshes/$part.obj" --drops 200 --format json -q --threads 2 >"$tmp/poses.json" 2>"$tmp/err"
  status=$?
  { echo "-- stderr"; cat "$tmp/err"; echo "-- exit $status"; } >>"$tmp/poses.json"
  compare "rbsim poses $part" "$tmp/poses.json" "$here/rbsim/poses_$part.json"
done

echo "golden: $passed passed, $failed failed$([ $skipped -gt 0 ] && echo ", $skipped long scenes left to the Release run")"
[ $failed -eq 0 ]
