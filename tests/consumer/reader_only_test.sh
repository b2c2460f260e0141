#!/usr/bin/env bash
# The reader-only consumer: neither it nor libmassprops_io depends on CGAL, GMP, MPFR or
# massprops::repair, and it still computes (and repairs, through the seam) the T-handle.
#   reader_only_test.sh READER_ONLY_PROGRAM IO_LIBRARY MESH_DIR
set -euo pipefail
program=$1 io=$2 meshes=$3
for f in "$program" "$io"; do
  needed=$(readelf -d "$f" | grep NEEDED || true)
  if echo "$needed" | grep -Eiq 'gmp|mpfr|cgal|massprops_repair'; then
    echo "reader_only_test: $f depends on CGAL's libraries:"
    echo "$needed"
    exit 1
  fi
done
# Loaded libraries before the repair is asked for: none of CGAL's.
"$program" "$meshes"
echo "reader_only_test: reads without CGAL; the repair step is reached when asked for"
