#!/usr/bin/env bash
# Installs what sombra needs from Debian 12's packages:
#
#   tools/install-deps.sh          building and rendering (tools/demo.sh, the .deb's users, Python)
#   tools/install-deps.sh --test   that, and what the tests, CI and the benchmarks need (tools/test.sh, .ci/run)
#
# Idempotent: installs only what is missing, and does nothing when all is there.
set -euo pipefail
case "${1:-}" in
  '') testing=false ;;
  --test) testing=true ;;
  *) echo "usage: tools/install-deps.sh [--test]" >&2; exit 2 ;;
esac

packages=(
  build-essential cmake ninja-build pkg-config
  libtinyobjloader-dev   # MTL parsing (and the OBJ load benchmark's yardstick)
  nlohmann-json3-dev     # scene JSON
  libtbb-dev             # parallel render loop and BVH build
  libpng-dev             # PNG output
  libjpeg-dev            # JPEG output (libjpeg-turbo)
  libopenexr-dev         # EXR output, EXR environment maps
  libstb-dev             # stb_image: textures (PNG, JPEG, TGA, BMP) and Radiance .hdr (headers in /usr/include/stb, libstb)
  libcli11-dev           # command line
  libeigen3-dev          # the denoiser's per-pixel regressions (header-only)
  libcpp-httplib-dev     # sombra view: the HTTP server on 127.0.0.1 (plain HTTP; the library is built with OpenSSL, zlib, Brotli)
  libtinygltf-dev        # glTF 2.0 parsing (header-only; src/io/gltf/gltf_file.cpp)
  libdraco-dev           # KHR_draco_mesh_compression
  libmeshoptimizer-dev   # EXT_meshopt_compression (decoders; the tests encode with it too)
  libwebp-dev            # WebP textures (EXT_texture_webp; the tests encode with it too)
  libopenvdb-dev         # grid media from OpenVDB files (spec §26; the tests write VDB files with it too)
  pybind11-dev python3-pybind11 python3-numpy  # the Python module (src/python/)
  python3-venv           # the set-up's .venv (tools/build.sh: .venv/bin/python imports sombra)
)
if $testing; then
  packages+=(
    assimp-testmodels      # tests: real and deliberately broken glTF 2.0 files (/usr/share/assimp/models/glTF2)
    libgtest-dev libgmock-dev  # tests
    libopenmpi-dev openmpi-bin  # mpirun -np K sombra render (optional: the build works without it)
    libembree-dev          # --accel embree, the BVH's yardstick (optional: the build works without it)
    python3-matplotlib     # tools/bench.sh: the big benchmark mesh and the cost-growth plot
    python3-pytest         # the Python module's tests
    jupyter-nbconvert python3-ipykernel  # tests: examples/tour.ipynb executed (jupyter-nbconvert --execute)
    lintian                # tools/package.sh: checks the .deb
    clang-14 libclang-rt-14-dev  # libFuzzer + sanitizer runtimes (tools/fuzz.sh)
    clang-tidy-14 clang-format-14  # tools/tidy.sh (CI: zero findings), .clang-format
    chromium                     # the viewer's end-to-end test (tools/browser/viewer_e2e.mjs), headless
  )
  # Node.js for that test's driver (playwright-core, from npm below): the
  # machine's own when it has one, else Debian's.
  command -v node >/dev/null && command -v npm >/dev/null || packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "sombra: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# playwright-core drives Debian's chromium (it downloads no browser of its
# own), at the version package-lock.json pins, into tools/browser/node_modules.
browser="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/browser"
if $testing && [ ! -f "$browser/node_modules/playwright-core/package.json" ]; then
  echo "sombra: installing playwright-core (npm) in tools/browser" >&2
  (cd "$browser" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
