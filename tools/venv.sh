#!/usr/bin/env bash
# The set-up's virtual environment (spec §19): makes .venv at the checkout's
# root over Debian's /usr/bin/python3 and its packages (--system-site-packages:
# numpy, matplotlib, pytest from Debian), and makes the built package
# importable there with a .pth file naming build/release/python, so that
# `.venv/bin/python -c "import sombra"` works with no other step and sees each
# rebuild at once. Idempotent: creates .venv only when missing and rewrites
# the .pth only when its line differs. tools/build.sh runs it after a release
# build.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv"
package="$root/build/release/python"
fail() {
    echo "sombra: error: tools/venv.sh: $1" >&2
    exit 1
}

[ -d "$package/sombra" ] || fail "$package/sombra is missing (the release build makes it: tools/build.sh)"
if [ ! -e "$venv" ]; then
    /usr/bin/python3 -m venv --system-site-packages "$venv" || fail "/usr/bin/python3 -m venv failed (Debian's python3-venv installs it)"
fi
# An existing .venv must be this one: over /usr/bin/python3, with the system's packages.
config="$venv/pyvenv.cfg"
grep -qx 'home = /usr/bin' "$config" 2>/dev/null && grep -qx 'include-system-site-packages = true' "$config" ||
    fail "$venv is not a venv over /usr/bin/python3 with --system-site-packages (remove it and run again)"

site="$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_path("purelib"))')"
pth="$site/sombra-build.pth"
if [ "$(cat "$pth" 2>/dev/null)" != "$package" ]; then
    printf '%s\n' "$package" >"$pth"
fi
"$venv/bin/python" -c "import sombra" || fail "$venv/bin/python cannot import sombra from $package"
