#!/usr/bin/env bash
# The README's first command: install what is missing, build, and path-trace
# the bundled default scene (the Cornell box lit by its ceiling light) to
# cornell-box.png.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/build.sh"
"$root/build/release/src/app/sombra" render "$root/scenes/cornell-box-path.json" -o "${1:-cornell-box.png}"
