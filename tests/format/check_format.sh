#!/usr/bin/env bash
# Every C++ source and header the repository tracks is formatted by the root .clang-format (clang-format 14, Debian's
# clang-format-14): a file that differs fails this test, named with the command that formats it. Never skips: without
# clang-format-14 or git it fails.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
command -v clang-format-14 > /dev/null || { echo "FAIL: clang-format-14 is not installed (scripts/test_packages.txt)"; exit 1; }
command -v git > /dev/null && git rev-parse --is-inside-work-tree > /dev/null 2>&1 ||
  { echo "FAIL: not a git checkout: the tracked files cannot be listed"; exit 1; }
mapfile -t files < <(git ls-files '*.cpp' '*.h' '*.hpp' '*.cc')
[ "${#files[@]}" -gt 0 ] || { echo "FAIL: no C++ files found"; exit 1; }
bad=()
for f in "${files[@]}"; do
  [ -f "$f" ] || continue  # deleted in the working tree, not yet committed
  clang-format-14 --dry-run --Werror "$f" > /dev/null 2>&1 || bad+=("$f")
done
if [ "${#bad[@]}" -gt 0 ]; then
  echo "FAIL: ${#bad[@]} of ${#files[@]} files differ from .clang-format:"
  printf '  %s\n' "${bad[@]:0:40}"
  echo "format them with: clang-format-14 -i ${bad[*]:0:40}"
  exit 1
fi
echo "ok: ${#files[@]} files formatted as .clang-format says"
