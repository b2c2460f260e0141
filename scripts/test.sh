#!/usr/bin/env bash
# Quick start (2): install dependencies, build, and run the whole test suite through ctest.
# MASSPROPS_SANITIZE=ON runs it under AddressSanitizer + UndefinedBehaviorSanitizer instead.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=$(bash "$root/scripts/build.sh" | tail -n 1)
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)"
