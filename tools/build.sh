#!/usr/bin/env bash
# The set-up: installs what is missing and builds sombra (CMake preset
# "release" unless SOMBRA_PRESET says otherwise); after a release build with
# the Python module, makes .venv so that `.venv/bin/python` imports sombra
# (tools/venv.sh). tools/demo.sh and tools/test.sh start with it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
preset="${SOMBRA_PRESET:-release}"
"$root/tools/install-deps.sh"
cd "$root"
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)"
if [ "$preset" = release ] && [ -d build/release/python/sombra ]; then
    tools/venv.sh
fi
