#!/usr/bin/env bash
# Checks (or with --fix applies) .clang-format on every C++ source of src/,
# bench/ and fuzz/ that git tracks. The check exits non-zero on any line that
# disagrees; CI runs it.
#
#   tools/format.sh          # check
#   tools/format.sh --fix    # reformat in place
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
format="${SOMBRA_CLANG_FORMAT:-clang-format-14}"
command -v "$format" >/dev/null || { echo "format.sh: $format not found (Debian: apt-get install clang-format-14)" >&2; exit 2; }
mapfile -t files < <(git ls-files 'src/*.cpp' 'src/*.h' 'bench/*.cpp' 'bench/*.h' 'fuzz/*.cpp' 'fuzz/*.h')
if [[ "${1:-}" == "--fix" ]]; then
  "$format" -i "${files[@]}"
else
  "$format" --dry-run --Werror "${files[@]}"
  echo "format.sh: ${#files[@]} files follow .clang-format" >&2
fi
