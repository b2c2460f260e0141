#!/usr/bin/env bash
# Checks that the C++ sources follow .clang-format (clang-format 14, Debian 12). Exit 1 and the
# files that differ otherwise; `git ls-files '*.cpp' '*.h' | xargs clang-format-14 -i` fixes them.
set -euo pipefail
cd "$(dirname "$0")/.."
bad=()
while IFS= read -r f; do
  clang-format-14 --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done < <(git ls-files '*.cpp' '*.h')
if [ ${#bad[@]} -gt 0 ]; then
  echo "check_format: these files do not follow .clang-format: ${bad[*]}"
  exit 1
fi
echo "check_format: every C++ file follows .clang-format"
