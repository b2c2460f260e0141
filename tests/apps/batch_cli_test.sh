#!/usr/bin/env bash
# massprops batch and merge, end to end: a folder with good, refused, malformed, crashing and
# hanging files gives one correct record per file; an interrupted output is resumed; shards merge
# into exactly the single run's output; the records' results are the command's JSON.
# Usage: batch_cli_test.sh MASSPROPS_BINARY DATA_DIR BATCH_FAULT_LIBRARY
set -u
bin=$1
data=$2
fault_lib=$3  # tests/fault/batch_fault.cpp: preloaded, it makes LoadSolid crash or hang on named files
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
passes=0
check() {  # check NAME CONDITION-EXIT-CODE
  if [ "$2" -eq 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
py=/usr/bin/python3
faulty() {  # faulty SPEC COMMAND...: COMMAND with the fault library preloaded, MASSPROPS_BATCH_FAULT=SPEC
  local spec=$1
  shift
  LD_PRELOAD=$fault_lib ASAN_OPTIONS="${ASAN_OPTIONS:-}:verify_asan_link_order=0" MASSPROPS_BATCH_FAULT=$spec "$@"
}

mkdir -p "$tmp/in/sub"
cp "$data/meshes/t_handle.obj" "$data/meshes/Moon.stl" "$data/meshes/spot.obj" "$tmp/in/"
cp "$data/meshes/ellipe0.003.off" "$data/meshes/box_0.1x0.2x0.3.gltf" "$tmp/in/sub/"
printf 'v 0 0 0\nf 1 2 3\n' >"$tmp/in/sub/malformed.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n' >"$tmp/in/sub/open.obj"
cp "$data/meshes/t_handle.obj" "$tmp/in/sub/crashme.obj"
cp "$data/meshes/t_handle.obj" "$tmp/in/sub/hangme.obj"
echo "not a mesh" >"$tmp/in/notes.txt"
cd "$tmp" || exit 1

# 1. One record per file, each with the right status; a crash and a hang do not stop the run.
faulty crash:crashme "$bin" batch in -o crash.jsonl --timeout 2 -q --jobs 2
[ $? -eq 0 ]; check "batch with a crashing file exits 0" $?
faulty hang:hangme "$bin" batch in -o full.jsonl --timeout 1 -q --jobs 2 --summary >summary.json
[ $? -eq 0 ]; check "batch with a hanging file exits 0" $?
$py - "$tmp" <<'PY'
import json, sys
tmp = sys.argv[1]
full = [json.loads(l) for l in open(f"{tmp}/full.jsonl")]
crash = [json.loads(l) for l in open(f"{tmp}/crash.jsonl")]
status = {r["file"]: r["status"] for r in full}
want = {"in/Moon.stl": "ok", "in/spot.obj": "ok", "in/t_handle.obj": "ok", "in/sub/box_0.1x0.2x0.3.gltf": "ok",
        "in/sub/ellipe0.003.off": "refused", "in/sub/open.obj": "refused", "in/sub/malformed.obj": "error",
        "in/sub/crashme.obj": "ok", "in/sub/hangme.obj": "timeout"}
assert status == want, status
assert [r["index"] for r in full] == list(range(9)) and all(r["of"] == 9 for r in full)
assert {r["file"]: r["status"] for r in crash}["in/sub/crashme.obj"] == "crashed"
assert "signal 11" in [r for r in crash if r["file"] == "in/sub/crashme.obj"][0]["message"]
assert "open mesh" in [r for r in full if r["file"] == "in/sub/open.obj"][0]["message"]
s = json.load(open(f"{tmp}/summary.json"))
assert (s["files"], s["ok"], s["refused"], s["error"], s["timeout"], s["crashed"]) == (9, 5, 2, 1, 1, 0), s
assert s["refused_by_reason"] == {"inward": 1, "open": 1}, s
PY
check "records and summary" $?

# 2. A record's result is the command's JSON for that file.
"$bin" in/t_handle.obj --format json -q >single.json
$py -c "
import json
rec = [json.loads(l) for l in open('full.jsonl') if 'in/t_handle.obj' in l][0]
assert rec['result'] == json.load(open('single.json'))
"
check "a record's result equals massprops --format json" $?

# 3. Resume: an output cut in the middle of a record is finished, with the same records.
faulty hang:hangme "$bin" batch in -o ref.jsonl --timeout 1 -q --jobs 1
head -c "$(($(head -n 4 ref.jsonl | wc -c) + 40))" ref.jsonl >cut.jsonl  # 4 records and a torn fifth
faulty hang:hangme "$bin" batch in -o cut.jsonl --resume --timeout 1 -q
[ $? -eq 0 ] && cmp -s cut.jsonl ref.jsonl; check "resume finishes a torn output into the same file" $?
"$bin" batch in -o ref.jsonl -q 2>err.txt
[ $? -eq 2 ] && grep -q "exists: --resume" err.txt; check "an existing output is not overwritten" $?
cmp -s ref.jsonl full.jsonl; check "same records whatever --jobs" $?

# 4. Shards: a manifest in two slices, merged, is the single run; a missing shard is found.
find in -type f \( -name '*.obj' -o -name '*.stl' -o -name '*.off' -o -name '*.gltf' \) | sort >manifest.txt
faulty hang:hangme "$bin" batch manifest.txt -o s0.jsonl --shard 0/2 --timeout 1 -q
faulty hang:hangme "$bin" batch manifest.txt -o s1.jsonl --shard 1/2 --timeout 1 -q
"$bin" merge merged.jsonl s1.jsonl s0.jsonl
[ $? -eq 0 ] && cmp -s merged.jsonl full.jsonl; check "shards merge into the single run's output" $?
"$bin" merge incomplete.jsonl s0.jsonl 2>err.txt
[ $? -eq 1 ] && grep -q "4 of 9 files have no record" err.txt && [ ! -e incomplete.jsonl ]
check "merge finds a missing shard and writes nothing" $?
"$bin" merge twice.jsonl s0.jsonl s0.jsonl s1.jsonl 2>err.txt
[ $? -eq 1 ] && grep -q "more than one record" err.txt; check "merge finds a shard given twice" $?

# 5. Pictures: one per computed file, named in its record; stems that repeat get the index.
mkdir -p twins/a twins/b && cp in/spot.obj twins/a/part.obj && cp in/spot.obj twins/b/part.obj
"$bin" batch twins -o pics.jsonl --pictures pics --picture-format png -q
[ $? -eq 0 ] && [ "$(grep -c '"picture":"pics/part-[01].png"' pics.jsonl)" -eq 2 ] && [ "$(ls pics | wc -l)" -eq 2 ] &&
  [ "$(head -c 4 pics/part-0.png | tail -c 3)" = PNG ]
check "batch --pictures draws each file, named in its record" $?
"$bin" batch twins -o pics2.jsonl --pictures pics.jsonl 2>err.txt
[ $? -eq 2 ] && grep -q "is not a folder" err.txt; check "--pictures must be a folder" $?

# 6. Arguments.
"$bin" batch in/spot.obj -o x.jsonl 2>err.txt
[ $? -eq 2 ] && grep -q "not a mesh file" err.txt; check "a mesh file is not a manifest" $?
"$bin" batch in -o y.jsonl --shard 2/2 2>err.txt
[ $? -eq 2 ] && grep -q "0 <= i < n" err.txt; check "--shard out of range" $?
"$bin" batch in 2>err.txt
[ $? -eq 2 ] && grep -q "needs -o" err.txt; check "batch needs -o" $?
"$bin" in/spot.obj --jobs 2 2>err.txt
[ $? -eq 2 ]; check "--jobs outside batch refused" $?

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
