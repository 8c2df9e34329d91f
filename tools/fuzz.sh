#!/usr/bin/env bash
# Builds the libFuzzer targets (CMake preset "fuzz", clang) and runs each for
# a given time with its seed corpus, side by side: one per core
# (SOMBRA_FUZZ_JOBS sets how many at once).
#
#   tools/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default: 60 s; obj ply scene gltf texture view shard vdb)
#
# Targets: obj (OBJ + MTL), ply, scene (scene JSON down to loaded meshes),
# gltf (.gltf / .glb through tinygltf and Draco), texture (an image file
# through sombra's texture loading), vdb (an OpenVDB file through the grid
# medium reader); see fuzz/fuzz_harness.h. Corpora grow in
# build/fuzz/corpus/TARGET (seeded from ../shared/objsuite, the small
# ../shared/models, scenes/ and ../shared/scenes, fuzz/seeds/gltf,
# ../shared/models/gltf and the assimp glTF2 test models, fuzz/seeds/texture
# and the small images of scenes/ and assimp-testmodels;
# nothing is written into the repository). Exits non-zero when a target finds
# a crash, leak, timeout or out-of-memory, and prints the reproducer's path:
# replay it with  build/fuzz/fuzz/fuzz_TARGET REPRODUCER  and, once fixed, add it
# to fuzz/regressions/TARGET/ (src/io/fuzz_regression_test.cpp replays those;
# src/image/exr_reader_test.cpp replays shard's).
# Every run is appended to build/fuzz/runs.tsv (date, target, seconds run, result, inputs run).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
[ $# -gt 0 ] && shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(obj ply scene gltf texture view shard vdb)
case "$seconds" in
  '' | *[!0-9]*) echo "usage: tools/fuzz.sh [SECONDS_PER_TARGET] [obj|ply|scene|gltf|texture|view|shard|vdb ...]" >&2; exit 2 ;;
esac
for t in "${targets[@]}"; do
  case "$t" in obj | ply | scene | gltf | texture | view | shard | vdb) ;; *) echo "fuzz.sh: unknown target '$t' (obj, ply, scene, gltf, texture, view, shard, vdb)" >&2; exit 2 ;; esac
done

shared="${SOMBRA_SHARED_DIR:-$root/../shared}"
build="$root/build/fuzz"
cd "$root"
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz

# The targets write each input to files under TMPDIR: memory, not disk.
scratch_base=/dev/shm
[ -d "$scratch_base" ] && [ -w "$scratch_base" ] || scratch_base="${TMPDIR:-/tmp}"
scratch="$(mktemp -d "$scratch_base/sombra-fuzz.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT

# Copies a seed into a corpus folder unless it is there already.
add_seed() {  # add_seed CORPUS NAME < bytes
  local out="$1/seed-$2"
  if [ -e "$out" ]; then cat >/dev/null; else cat >"$out"; fi
}

# OBJ seeds: each OBJ with its first MTL file appended after the "#MTL" line
# (fuzz_harness.h), its mtllib pointed at the m.mtl the target writes.
seed_obj() {
  local corpus="$1" obj name mtl
  local files=()
  [ -d "$shared/objsuite" ] && while IFS= read -r -d '' obj; do files+=("$obj"); done \
    < <(find "$shared/objsuite" -name '*.obj' -print0)
  [ -d "$shared/models" ] && while IFS= read -r -d '' obj; do files+=("$obj"); done \
    < <(find "$shared/models" -name '*.obj' -size -400k -print0)
  for obj in "${files[@]}" "$root"/scenes/models/*.obj; do
    name="$(basename "$(dirname "$obj")")-$(basename "$obj" .obj | tr -c 'A-Za-z0-9_.\n-' '_')"
    mtl=""
    while read -r lib; do
      [ -f "$(dirname "$obj")/$lib" ] && { mtl="$(dirname "$obj")/$lib"; break; }
    done < <(sed -n 's/^[[:space:]]*mtllib[[:space:]]\+//p' "$obj" | tr -d '\r' | tr ' ' '\n')
    if [ -n "$mtl" ]; then
      { sed 's/^\([[:space:]]*\)mtllib[[:space:]].*/\1mtllib m.mtl/' "$obj"; printf '\n#MTL\n'; cat "$mtl"; } |
        add_seed "$corpus" "$name"
    else
      add_seed "$corpus" "$name" <"$obj"
    fi
  done
}

# PLY seeds: ascii and both binary byte orders, with and without normals,
# faces before vertices, extra elements and properties; plus the start of the
# dragon's header. (printf formats: \n and \xHH are bytes.)
seed_ply() {
  local corpus="$1"
  local ascii='ply\nformat ascii 1.0\n' le='ply\nformat binary_little_endian 1.0\n'
  local be='ply\nformat binary_big_endian 1.0\n'
  local xyz='property float x\nproperty float y\nproperty float z\n'
  local nxyz='property float nx\nproperty float ny\nproperty float nz\n'
  local faces='property list uchar int vertex_indices\n'
  local zero='\x00\x00\x00\x00' one_le='\x00\x00\x80\x3f' one_be='\x3f\x80\x00\x00'
  { printf "${ascii}comment quad\nelement vertex 4\n${xyz}element face 2\n${faces}end_header\n"
    printf '0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n'; } | add_seed "$corpus" ascii-quad
  { printf "${ascii}element vertex 3\n${xyz}${nxyz}property uchar red\n"
    printf 'element face 1\nproperty list uchar uint vertex_index\nproperty int flags\n'
    printf 'element edge 1\nproperty int a\nproperty list ushort float b\nend_header\n'
    printf '0 0 0 0 0 1 255\n1 0 0 0 0 1 0\n0 1 0 0 0 1 9\n3 0 1 2 7\n5 2 1.5 -2\n'; } |
    add_seed "$corpus" ascii-normals-extra
  { printf "ply\r\nformat ascii 1.0\r\nelement face 1\r\n${faces//\\n/\\r\\n}element vertex 5\r\n"
    printf "${xyz//\\n/\\r\\n}end_header\r\n5 0 1 2 3 4\r\n0 0 0\r\n2 0 0\r\n2 2 0\r\n1 0.5 0\r\n0 2 0\r\n"; } |
    add_seed "$corpus" ascii-crlf-faces-first
  { printf "${le}element vertex 3\n${xyz}element face 1\n${faces}end_header\n"
    printf "${zero}${zero}${zero}${one_le}${zero}${zero}${zero}${one_le}${zero}"
    printf '\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00'; } | add_seed "$corpus" binary-le-triangle
  { printf "${be}element vertex 3\n${xyz}${nxyz}element face 1\n${faces}end_header\n"
    printf "${zero}${zero}${zero}${zero}${zero}${one_be}"
    printf "${one_be}${zero}${zero}${zero}${zero}${one_be}"
    printf "${zero}${one_be}${zero}${zero}${zero}${one_be}"
    printf '\x03\x00\x00\x00\x00\x00\x00\x00\x01\x00\x00\x00\x02'; } | add_seed "$corpus" binary-be-normals
  [ -f "$shared/models/dragon.ply" ] && head -c 4096 "$shared/models/dragon.ply" | add_seed "$corpus" dragon-start
  return 0
}

# Scene seeds: every scene (and the version-2 seeds of fuzz/seeds/scene)
# with its objects' files pointed at the target's m.obj, and once more at m.ply.
seed_scene() {
  local corpus="$1" json name
  for json in "$root"/scenes/*.json "$shared"/scenes/*.json "$root"/fuzz/seeds/scene/*.json; do
    [ -f "$json" ] || continue
    name="$(basename "$json" .json)"
    sed 's/"file"[[:space:]]*:[[:space:]]*"[^"]*"/"file": "m.obj"/g' "$json" | add_seed "$corpus" "$name-obj"
    sed 's/"file"[[:space:]]*:[[:space:]]*"[^"]*"/"file": "m.ply"/g' "$json" | add_seed "$corpus" "$name-ply"
  done
}

# glTF seeds: the hand-made ones of fuzz/seeds/gltf (tools/make-gltf-seeds.py),
# ../shared's Draco bunny, and every assimp glTF2 test model under 64 KiB
# (those with external .bin files load without them: the target writes one file).
seed_gltf() {
  local corpus="$1" f
  for f in "$root"/fuzz/seeds/gltf/* "$shared"/models/gltf/*.gl[tb]*; do
    [ -f "$f" ] && add_seed "$corpus" "$(basename "$f")" <"$f"
  done
  if [ -d /usr/share/assimp/models/glTF2 ]; then
    while IFS= read -r -d '' f; do
      add_seed "$corpus" "assimp-$(echo "${f#/usr/share/assimp/models/glTF2/}" | tr '/' '_')" <"$f"
    done < <(find /usr/share/assimp/models/glTF2 \( -name '*.gltf' -o -name '*.glb' \) -size -64k -print0)
  fi
  return 0
}

# Texture seeds: the small images written for it (fuzz/seeds/texture: PNG of
# 8 and 16 bits, grey, alpha, palettes, baseline and progressive JPEG, TGA
# plain and RLE, BMP, Radiance HDR, EXR), the scenes' own textures, and the
# images of Debian's assimp-testmodels under 64 KiB when installed.
seed_texture() {
  local corpus="$1" image
  local files=("$root"/fuzz/seeds/texture/* "$root"/scenes/textures/*)
  [ -d /usr/share/assimp/models ] && while IFS= read -r -d '' image; do files+=("$image"); done \
    < <(find /usr/share/assimp/models -type f \( -iname '*.png' -o -iname '*.jpg' -o -iname '*.jpeg' -o -iname '*.tga' \
          -o -iname '*.bmp' -o -iname '*.hdr' -o -iname '*.exr' \) -size -64k -print0)
  for image in "${files[@]}"; do
    [ -f "$image" ] || continue
    add_seed "$corpus" "$(basename "$(dirname "$image")")-$(basename "$image" | tr -c 'A-Za-z0-9_.\n-' '_')" <"$image"
  done
}

# View seeds: host, origin, token and a query value, NUL-separated (fuzz/fuzz_view.cpp).
seed_view() {
  local corpus="$1"
  printf '127.0.0.1:8765\x00http://127.0.0.1:8765\x000123456789abcdef0123456789abcdef\x000.5,1,-2e3' |
    add_seed "$corpus" allowed
  printf 'evil.example:8765\x00http://evil.example\x00wrong\x0016' | add_seed "$corpus" foreign
  printf 'localhost:8765\x00\x00\x001e39' | add_seed "$corpus" no-token
}

# Shard seeds: EXR files sombra render --shard wrote (fuzz/seeds/shard),
# and PFM files (the target reads an input starting with 'P' as one):
# colour and grey, both byte orders, a comment-free minimal header.
seed_shard() {
  local corpus="$1" f
  for f in "$root"/fuzz/seeds/shard/*.exr; do add_seed "$corpus" "$(basename "$f")" <"$f"; done
  { printf 'PF\n2 1\n-1.0\n'; printf '\x00\x00\x80\x3f%.0s' 1 2 3 4 5 6; } | add_seed "$corpus" colour-le.pfm
  { printf 'Pf\n1 2\n1.0\n'; printf '\x3f\x80\x00\x00\x40\x00\x00\x00'; } | add_seed "$corpus" grey-be.pfm
  { printf 'PF 1 1 -2.5 '; printf '\x00\x00\xc0\x7f\x00\x00\x80\x7f\x00\x00\x00\x00'; } | add_seed "$corpus" nan-inf.pfm
}

# VDB seeds: small OpenVDB files (fuzz/seeds/vdb: voxels, an active tile
# with zip compression, a float grid beside a vec3 one).
seed_vdb() {
  local corpus="$1" f
  for f in "$root"/fuzz/seeds/vdb/*.vdb; do add_seed "$corpus" "$(basename "$f")" <"$f"; done
}

# Runs one target for $seconds; its verdict goes to $build/verdict_TARGET
# (the targets run side by side, one per core).
fuzz_one() {
  local t="$1" corpus="$build/corpus/$1" artifacts="$build/artifacts/$1" log="$build/fuzz_$1.log"
  local before result=clean started=$SECONDS elapsed runs found extra=() asan_options="${ASAN_OPTIONS:-}"
  mkdir -p "$corpus" "$artifacts" "$scratch/$t"
  "seed_$t" "$corpus"
  echo "fuzz.sh: fuzz_$t for $seconds s ($(find "$corpus" -type f | wc -l) inputs in $corpus; log $log)" >&2
  before="$(find "$artifacts" -type f | sort)"
  [ "$t" = vdb ] && extra=(-malloc_limit_mb=1048576 -timeout=30) &&
    asan_options="${asan_options:+$asan_options:}max_allocation_size_mb=1024"
  TMPDIR="$scratch/$t" LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp:print_suppressions=0" ASAN_OPTIONS="$asan_options" \
    "$build/fuzz/fuzz_$t" "$corpus" -dict="$root/fuzz/$t.dict" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 "${extra[@]}" \
    -artifact_prefix="$artifacts/" -print_final_stats=1 >"$log" 2>&1 || result=failed
  elapsed=$((SECONDS - started))
  runs="$(sed -n 's/^stat::number_of_executed_units:[[:space:]]*//p' "$log" | tail -1)"
  printf '%s\t%s\t%s\t%s\t%s\n' "$(date -u +%FT%TZ)" "$t" "$elapsed" "$result" "${runs:-?}" >>"$build/runs.tsv"
  echo "$result" >"$build/verdict_$t"
  if [ "$result" = clean ]; then
    echo "fuzz.sh: fuzz_$t clean: ${runs:-?} inputs in $elapsed s" >&2
    return
  fi
  found="$(comm -13 <(echo "$before") <(find "$artifacts" -type f | sort) | sed '/^$/d')"
  { tail -n 40 "$log"; echo "fuzz.sh: fuzz_$t FAILED; reproducer: ${found:-(none written; see $log)}"; } >&2
}

parallel="${SOMBRA_FUZZ_JOBS:-$(nproc)}"
for t in "${targets[@]}"; do
  rm -f "$build/verdict_$t"
  while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do wait -n || true; done
  fuzz_one "$t" &
done
wait
status=0
for t in "${targets[@]}"; do
  [ "$(cat "$build/verdict_$t" 2>/dev/null)" = clean ] || status=1
done
exit "$status"
