#!/usr/bin/env bash
# The set-up: installs what is missing and builds sombra (CMake preset
# "release" unless SOMBRA_PRESET says otherwise); after a release build with
# the Python module, makes .venv so that `.venv/bin/python` imports sombra
# (tools/venv.sh). tools/demo.sh starts with it; tools/test.sh with
# `tools/build.sh --tests`, which also installs what the tests need and
# builds them.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
preset="${SOMBRA_PRESET:-release}"
case "${1:-}" in
  '') tests=OFF ;;
  --tests) tests=ON ;;
  *) echo "usage: tools/build.sh [--tests]" >&2; exit 2 ;;
esac
if [ "$tests" = ON ]; then "$root/tools/install-deps.sh" --test; else "$root/tools/install-deps.sh"; fi
cd "$root"
cmake --preset "$preset" -DSOMBRA_BUILD_TESTS="$tests" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)"
if [ "$preset" = release ] && [ -d build/release/python/sombra ]; then
    tools/venv.sh
fi
