#!/usr/bin/env bash
# Runs clang-tidy 14 with the repository's .clang-tidy over every .cpp of src/
# (tests included) that the release build compiles, reading the flags from
# build/release/compile_commands.json (configuring the release preset first
# when it is missing). sombra's own headers under src/ are checked through the
# files that include them (HeaderFilterRegex in .clang-tidy). Every finding is
# an error: the script exits non-zero on any, and 0 only on a clean tree.
#
#   tools/tidy.sh                 # all of src/, SOMBRA_TIDY_JOBS at a time (default: nproc)
#   tools/tidy.sh src/render      # only the files whose path matches these regular expressions
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
jobs="${SOMBRA_TIDY_JOBS:-$(nproc)}"
tidy="${SOMBRA_CLANG_TIDY:-clang-tidy-14}"
command -v "$tidy" >/dev/null || { echo "tidy.sh: $tidy not found (Debian: apt-get install clang-tidy-14)" >&2; exit 2; }

db=build/release/compile_commands.json
if [ ! -f "$db" ]; then
  cmake --preset release >/dev/null
fi
# Headers the build generates (the viewer's embedded page), which some
# sources include: made here too, so that a fresh clone needs no build first.
cmake --build build/release --target sombra_view_page >/dev/null

# The translation units: src/'s .cpp files in the database (optional backends
# the build did not find are not compiled, so not checked), narrowed by any
# path patterns given.
mapfile -t files < <(python3 - "$db" "$root/src/" "$@" <<'EOF'
import json, re, sys
db, src, patterns = sys.argv[1], sys.argv[2], sys.argv[3:]
seen = set()
for entry in json.load(open(db)):
    f = entry["file"]
    if f.startswith(src) and f.endswith(".cpp") and f not in seen:
        if not patterns or any(re.search(p, f) for p in patterns):
            seen.add(f)
            print(f)
EOF
)
[ ${#files[@]} -gt 0 ] || { echo "tidy.sh: no source file matches" >&2; exit 2; }
echo "tidy.sh: $tidy on ${#files[@]} files, $jobs at a time" >&2

start=$(date +%s)
status=0
if command -v run-clang-tidy-14 >/dev/null && [ "$tidy" = clang-tidy-14 ]; then
  # run-clang-tidy-14 takes regular expressions; a wrapper adds
  # --warnings-as-errors, which it has no option for.
  wrapper="$(mktemp)"
  trap 'rm -f "$wrapper"' EXIT
  printf '#!/bin/sh\nexec clang-tidy-14 --warnings-as-errors="*" "$@"\n' >"$wrapper"
  chmod +x "$wrapper"
  patterns=()
  for f in "${files[@]}"; do patterns+=("^$(printf '%s' "$f" | sed 's/[][\.*^$+?(){}|]/\\&/g')\$"); done
  run-clang-tidy-14 -quiet -j "$jobs" -p build/release -clang-tidy-binary "$wrapper" "${patterns[@]}" || status=$?
else
  printf '%s\0' "${files[@]}" |
    xargs -0 -n 1 -P "$jobs" "$tidy" --quiet --warnings-as-errors='*' -p build/release || status=$?
fi
echo "tidy.sh: $(( $(date +%s) - start )) s, $([ $status -eq 0 ] && echo 'no findings' || echo 'FINDINGS (see above)')" >&2
exit $status
