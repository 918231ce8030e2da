#!/usr/bin/env bash
# Checks that every C++ source in the repository is laid out as .clang-format says (Google's
# style at 100 columns); prints the files that are not and exits 1. With --fix, formats them.
#
#   tools/check-format.sh [--fix] [SOURCE_DIR]
set -uo pipefail
fix=0
if [ "${1:-}" = "--fix" ]; then fix=1; shift; fi
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root" || exit 2
format=$(command -v clang-format || command -v clang-format-14) ||
  { echo "check-format: clang-format is not installed (tools/install-deps.sh installs it)"; exit 2; }
mapfile -t files < <(git ls-files common materials generator formats imaging scene tracer app tests bench |
                      grep -E '\.(h|cpp)$')
if [ "$fix" -eq 1 ]; then
  "$format" -i "${files[@]}"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  "$format" --dry-run --Werror "$f" > /dev/null 2>&1 || bad+=("$f")
done
if [ "${#bad[@]}" -gt 0 ]; then
  printf 'check-format: not laid out as .clang-format says: %s\n' "${bad[@]}"
  echo "check-format: tools/check-format.sh --fix formats them"
  exit 1
fi
echo "check-format: ${#files[@]} files laid out as .clang-format says"
