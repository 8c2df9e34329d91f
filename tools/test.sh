#!/usr/bin/env bash
# The README's second command: install what is missing, build, and run the
# whole test suite through CTest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/build.sh" --tests
cd "$root"
ctest --preset release
