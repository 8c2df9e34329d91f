#!/usr/bin/env bash
# The README's first command: install what is missing, build, and render the
# bundled default scene (the Cornell box) to cornell-box.png.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/build.sh"
"$root/build/release/src/app/sombra" render "$root/scenes/cornell-box.json" -o "${1:-cornell-box.png}"
