#!/usr/bin/env bash
# Builds sombra's .debs with CPack from the release build and checks them:
#   - sombra: dpkg-deb -c lists the binary, the man page, the Python
#     package, the copyright and changelog; its Depends name the libraries
#     and Python, and no MPI (it only suggests sombra-mpi);
#   - sombra-mpi: the MPI plugin, depending on Open MPI and this sombra;
#     sombra-embree: the Embree plugin, depending on Embree and this sombra;
#   - lintian reports no error (its warnings are printed; docs/install.md
#     says which remain and why);
#   - the packages extracted into a throwaway folder (dpkg -x, nothing is
#     installed on this system) run: bin/sombra --version and a render, and
#     /usr/bin/python3 imports sombra from the extracted tree and renders;
#     sombra alone refuses mpirun and --accel embree in one line; with
#     sombra-mpi beside it mpirun -np 2 writes the single process's bytes,
#     with sombra-embree --accel embree renders.
# Prints the .debs' paths last. CI (.ci/run) runs it after tools/test.sh.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
fail() {
    echo "sombra: error: tools/package.sh: $1" >&2
    exit 1
}

tools/build.sh >/dev/null
out=build/release/package
rm -f "$out"/sombra_*.deb "$out"/sombra-mpi_*.deb "$out"/sombra-embree_*.deb
cpack --config build/release/CPackConfig.cmake -B "$out" >"$out.log" 2>&1 || {
    cat "$out.log" >&2
    fail "cpack failed (its log: $out.log)"
}
debs=("$out"/sombra_*.deb)
[ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ] || fail "cpack made no single sombra_*.deb in $out"
deb="${debs[0]}"
mpi_debs=("$out"/sombra-mpi_*.deb)
mpi_deb=""
[ -f "${mpi_debs[0]}" ] && mpi_deb="${mpi_debs[0]}"
[ -n "$mpi_deb" ] || [ -z "${SOMBRA_REQUIRE_MPI:-}" ] || fail "cpack made no sombra-mpi_*.deb (is Open MPI installed?)"
embree_debs=("$out"/sombra-embree_*.deb)
embree_deb=""
[ -f "${embree_debs[0]}" ] && embree_deb="${embree_debs[0]}"
echo "== package: $deb"
dpkg-deb -f "$deb" Package Version Architecture Depends Suggests Section

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
! grep -qi "mpi" <<<"$depends" || fail "$deb depends on MPI, which only sombra-mpi should: $depends"
! grep -qi "embree" <<<"$depends" || fail "$deb depends on Embree, which only sombra-embree should: $depends"
# check_plugin_deb DEB PLUGIN LIBRARY: a plugin package holds its plugin and
# depends on its library's package and on this very sombra.
check_plugin_deb() {
    local plugin_deb="$1" plugin="./usr/lib/sombra/plugins/$2" plugin_depends needed
    echo "== package: $plugin_deb"
    dpkg-deb -f "$plugin_deb" Package Version Architecture Depends Section
    dpkg-deb -c "$plugin_deb" | awk '{print $NF}' | grep -qxF "$plugin" || fail "$plugin_deb lacks $plugin"
    plugin_depends="$(dpkg-deb -f "$plugin_deb" Depends)"
    for needed in "$3" "sombra (= $(dpkg-deb -f "$deb" Version))"; do
        grep -qF "$needed" <<<"$plugin_depends" || fail "$plugin_deb's Depends lacks $needed: $plugin_depends"
    done
}
[ -z "$mpi_deb" ] || check_plugin_deb "$mpi_deb" libsombra_mpi.so libopenmpi
[ -z "$embree_deb" ] || check_plugin_deb "$embree_deb" libsombra_embree.so libembree3

echo "== package: lintian (fails on errors; warnings listed)"
if command -v lintian >/dev/null; then
    lintian --fail-on error --tag-display-limit 0 "$deb" $mpi_deb $embree_deb ||
        fail "lintian reports errors on $deb $mpi_deb $embree_deb"
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

# mpirun: refused in one line without the plugin, the single process's bytes with it.
if [ -n "$mpi_deb" ] && command -v mpirun >/dev/null; then
    echo "== package: mpirun without and with sombra-mpi"
    mpi_run() {
        OMPI_MCA_btl_vader_single_copy_mechanism=none timeout -k 5 60 mpirun --allow-run-as-root --oversubscribe \
            -np 2 "$tree/usr/bin/sombra" render scenes/cornell-box.json --width 48 --height 32 --quiet -o "$1"
    }
    if mpi_run "$tree/mpi.png" 2>"$tree/mpi.err"; then fail "the sombra package alone ran under mpirun"; fi
    grep -q "install the sombra-mpi package" "$tree/mpi.err" || fail "without sombra-mpi, mpirun said: $(cat "$tree/mpi.err")"
    dpkg -x "$mpi_deb" "$tree"
    mpi_run "$tree/mpi.png" || fail "with sombra-mpi extracted beside it, mpirun -np 2 sombra failed"
    "$tree/usr/bin/sombra" render scenes/cornell-box.json --width 48 --height 32 --quiet -o "$tree/one.png"
    cmp -s "$tree/mpi.png" "$tree/one.png" || fail "mpirun -np 2 wrote other bytes than one process"
    echo "mpirun -np 2 from the extracted packages wrote the single process's image"
fi
# --accel embree: refused in one line without its plugin, rendered with it.
if [ -n "$embree_deb" ]; then
    echo "== package: --accel embree without and with sombra-embree"
    embree_run() { "$tree/usr/bin/sombra" render scenes/cornell-box.json --width 48 --height 32 --accel embree --quiet -o "$tree/embree.png"; }
    if embree_run 2>"$tree/embree.err"; then fail "the sombra package alone rendered with --accel embree"; fi
    grep -q "install the sombra-embree package" "$tree/embree.err" ||
        fail "without sombra-embree, --accel embree said: $(cat "$tree/embree.err")"
    dpkg -x "$embree_deb" "$tree"
    embree_run || fail "with sombra-embree extracted beside it, --accel embree failed"
    [ -s "$tree/embree.png" ] || fail "--accel embree wrote no image"
    echo "--accel embree renders from the extracted packages"
fi
echo "$deb"
[ -z "$mpi_deb" ] || echo "$mpi_deb"
[ -z "$embree_deb" ] || echo "$embree_deb"
