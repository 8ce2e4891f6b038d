#!/usr/bin/env bash
# Checks that the C and C++ files are formatted as .clang-format says (VTK's style): lists every
# file clang-format would change and exits 1 if there is one. Checks the files given as arguments,
# or every C/C++ file git tracks. Changes nothing; to format a file: clang-format -i <file>.
# CLANG_FORMAT names the program (default clang-format; the settings need version 14 or later).
set -euo pipefail
cd "$(dirname "$0")/.."
clang_format="${CLANG_FORMAT:-clang-format}"
if ! command -v "$clang_format" >/dev/null 2>&1; then
  echo "check_format: $clang_format not found (scripts/install-deps.sh installs it)" >&2
  exit 2
fi

if [ "$#" -gt 0 ]; then
  files=("$@")
else
  mapfile -t files < <(git ls-files -- '*.h' '*.hpp' '*.c' '*.cc' '*.cpp' '*.cxx' '*.txx')
fi

unformatted=0
for file in "${files[@]}"; do
  if ! "$clang_format" --style=file --dry-run --Werror "$file" >/dev/null 2>&1; then
    echo "check_format: $file is not formatted (clang-format -i $file)"
    unformatted=$((unformatted + 1))
  fi
done
echo "check_format: ${#files[@]} file(s) checked, $unformatted not formatted"
[ "$unformatted" -eq 0 ]
