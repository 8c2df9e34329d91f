#!/usr/bin/env bash
# Builds sombra's .deb with CPack from the release build and checks it:
#   - dpkg-deb -c lists the binary, the man page, the Python package, the
#     copyright and changelog; its Depends name the libraries and Python;
#   - lintian reports no error (its warnings are printed; docs/install.md
#     says which remain and why);
#   - the package extracted into a throwaway folder (dpkg -x, nothing is
#     installed on this system) runs: bin/sombra --version and a render, and
#     /usr/bin/python3 imports sombra from the extracted tree and renders.
# Prints the .deb's path last. CI (.ci/run) runs it after tools/test.sh.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
fail() {
    echo "sombra: error: tools/package.sh: $1" >&2
    exit 1
}

tools/build.sh >/dev/null
out=build/release/package
rm -f "$out"/sombra_*.deb
cpack --config build/release/CPackConfig.cmake -B "$out" >"$out.log" 2>&1 || {
    cat "$out.log" >&2
    fail "cpack failed (its log: $out.log)"
}
debs=("$out"/sombra_*.deb)
[ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ] || fail "cpack made no single sombra_*.deb in $out"
deb="${debs[0]}"
echo "== package: $deb"
dpkg-deb -f "$deb" Package Version Architecture Depends Section

echo "== package: contents (dpkg-deb -c)"
contents="$(dpkg-deb -c "$deb" | awk '{print $NF}')"
for path in ./usr/bin/sombra ./usr/share/man/man1/sombra.1.gz ./usr/share/doc/sombra/copyright \
    ./usr/share/doc/sombra/changelog.gz ./usr/lib/python3/dist-packages/sombra/__init__.py \
    ./usr/lib/python3/dist-packages/sombra/_options.py ./usr/lib/python3/dist-packages/sombra/_progress.py \
    ./usr/lib/python3/dist-packages/sombra/_scene.py ./usr/lib/python3/dist-packages/sombra/_sombra.pyi \
    ./usr/lib/python3/dist-packages/sombra/py.typed ./usr/share/bash-completion/completions/sombra \
    ./usr/share/zsh/vendor-completions/_sombra ./usr/share/sombra/examples/cornell-box-path.json \
    ./usr/share/sombra/examples/models/cornell-box-empty.obj ./usr/share/sombra/examples/textures/checker.png; do
    grep -qxF "$path" <<<"$contents" || fail "$deb lacks $path"
done
grep -qE '^\./usr/lib/python3/dist-packages/sombra/_sombra\.cpython-[0-9]+-.*\.so$' <<<"$contents" ||
    fail "$deb lacks the extension usr/lib/python3/dist-packages/sombra/_sombra.cpython-*.so"
grep -E '^\./usr/(bin|share/man|lib/python3)/.*[^/]$' <<<"$contents"
depends="$(dpkg-deb -f "$deb" Depends)"
for needed in libtbb12 libpng16-16 python3-numpy 'python3 (>='; do
    grep -qF "$needed" <<<"$depends" || fail "$deb's Depends lacks $needed: $depends"
done

echo "== package: lintian (fails on errors; warnings listed)"
if command -v lintian >/dev/null; then
    lintian --fail-on error --tag-display-limit 0 "$deb" || fail "lintian reports errors on $deb"
else
    echo "lintian is not installed (tools/install-deps.sh --test installs it): not run"
    [ -z "${SOMBRA_REQUIRE_LINTIAN:-}" ] || fail "lintian is missing and SOMBRA_REQUIRE_LINTIAN is set"
fi

echo "== package: the extracted tree runs"
tree="$(mktemp -d)"
trap 'rm -rf "$tree"' EXIT
dpkg -x "$deb" "$tree"
"$tree/usr/bin/sombra" --version
"$tree/usr/bin/sombra" render scenes/cornell-box.json --width 32 --height 32 --quiet -o "$tree/cornell.png"
[ -s "$tree/cornell.png" ] || fail "the extracted sombra wrote no image"
zcat "$tree/usr/share/man/man1/sombra.1.gz" | grep -q '^\.SH "SOMBRA RENDER"' || fail "the man page has no render section"
zcat "$tree/usr/share/man/man1/sombra.1.gz" | grep -q '^\.SH EXAMPLES' || fail "the man page has no EXAMPLES"
# Every example scene renders from the installed copy, as the man page says to run them.
for scene in "$tree"/usr/share/sombra/examples/*.json; do
    "$tree/usr/bin/sombra" render "$scene" --width 24 --height 16 --spp 1 --quiet -o "$tree/example.png" ||
        fail "the installed example $(basename "$scene") does not render"
done
PYTHONPATH="$tree/usr/lib/python3/dist-packages" PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 -c '
import sys, sombra
assert sombra.__file__.startswith(sys.argv[1]), sombra.__file__
img = sombra.render(sombra.load("scenes/cornell-box.json"), width=16, height=16, spp=1)
assert img.shape == (16, 16, 3) and img.max() > 0
print("import sombra from", sombra.__file__, "renders", img.shape)' "$tree" ||
    fail "/usr/bin/python3 cannot import and render with sombra from the extracted package"
echo "$deb"
