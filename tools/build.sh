#!/usr/bin/env bash
# Installs what is missing and builds sombra (CMake preset "release" unless
# SOMBRA_PRESET says otherwise). Prints the path of the built binary's folder.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
preset="${SOMBRA_PRESET:-release}"
"$root/tools/install-deps.sh"
cd "$root"
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)"
