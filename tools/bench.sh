#!/usr/bin/env bash
# Runs sombra-bench and rewrites the measured parts of docs/performance.md:
# the machine, the date and the exact commands; the bvh-against-embree table
# over ../shared/scenes; OBJ loading against tinyobjloader; and cost growth
# from the dragon's resolutions up to a 105 M-triangle subdivision, with its
# plot (docs/performance-growth.png); and path tracing: bvh against embree
# on three path-traced scenes, the error against a converged reference
# (cached under build/bench; the first run renders it, about a minute), and
# allocation counts against spp. Everything else in that file is prose and
# stays as it is. Takes about 8 minutes on 2 cores, plus about 10 for the
# 105 M-triangle mesh (its own process, SOMBRA_BENCH_GROWTH_BIG_REPS rounds,
# default 1; it needs about 11 GB of memory and 2 GB of disk under build/);
# run it on a quiet machine (the load average at the start is recorded).
#
#   tools/bench.sh            # all of it
#   SOMBRA_BENCH_REPS=1 tools/bench.sh   # a quick run (fewer rounds)
#   SOMBRA_BENCH_BUILD=build-x tools/bench.sh   # another build folder
#   SOMBRA_BENCH_SECTIONS="path" tools/bench.sh  # only some sections (of
#       scenes load growth path); the machine block is then left alone and
#       each path block carries its own date, load and commands
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
reps="${SOMBRA_BENCH_REPS:-5}"
growth_reps="${SOMBRA_BENCH_GROWTH_REPS:-3}"
growth_big_reps="${SOMBRA_BENCH_GROWTH_BIG_REPS:-1}"
sections="${SOMBRA_BENCH_SECTIONS:-scenes load growth path}"
want() { [[ " $sections " == *" $1 "* ]]; }
build="${SOMBRA_BENCH_BUILD:-build/release}"  # relative to the repository root
out="build/bench"
shared="../shared"
# Debian's python3, where python3-numpy and python3-matplotlib live (a
# python3 earlier on PATH, e.g. from pyenv, may not have them).
python="${SOMBRA_PYTHON:-/usr/bin/python3}"

"$root/tools/install-deps.sh" --test
[ -d "$shared/scenes" ] || { echo "bench.sh: $root/$shared/scenes not found" >&2; exit 1; }
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target sombra-bench sombra -j "$(nproc)"
mkdir -p "$out"

load_at_start="$(cut -d' ' -f1-3 /proc/loadavg)"
commit="$(git rev-parse --short HEAD)"
git diff --quiet HEAD -- src bench CMakeLists.txt || commit="$commit + uncommitted changes"
if want growth; then
  [ -f build/bench-meshes/dragon-sub2.ply ] || "$python" tools/make-big-mesh.py --levels 2
  [ -f build/bench-meshes/dragon-split11.ply ] || "$python" tools/make-big-mesh.py --split 11
fi

bench="$build/bench/sombra-bench"
scenes_cmd="$bench scenes --reps $reps $shared/scenes/bunny.json $shared/scenes/dragon.json $shared/scenes/manylights.json $shared/scenes/cornell.json $shared/scenes/phong.json"
load_cmd="$bench load --reps $reps $shared/models/dragon.obj"
growth_cmd="$bench growth --reps $growth_reps --width 1280 --height 720 --csv $out/growth.csv $shared/models/dragon-res2.obj $shared/models/dragon.ply build/bench-meshes/dragon-sub1.ply build/bench-meshes/dragon-sub2.ply"
# The 105 M-triangle mesh in a process of its own, so that its peak memory
# is its own, with fewer rounds (a build takes minutes).
growth_big_cmd="$bench growth --reps $growth_big_reps --width 1280 --height 720 --csv $out/growth-big.csv build/bench-meshes/dragon-split11.ply"
plot_cmd="$python tools/plot-growth.py $out/growth.csv $out/growth-big.csv docs/performance-growth.png"

# Path tracing: 256×256 at 32 spp, depth 8 (1–3 s a render here); the
# error of the Cornell box against a 4096-spp reference at 128×128.
path_cmd="$bench path --reps $reps --width 256 --height 256 --spp 32 --max-depth 8 $shared/scenes/cornell.json $shared/scenes/dragon.json $shared/scenes/phong.json"
rays_cmd="$bench rays --reps 9 --rays 400000 $shared/scenes/cornell.json $shared/scenes/dragon.json $shared/scenes/bunny.json $shared/scenes/manylights.json"
# The same rays against Embree in its robust mode, which like sombra's BVH
# lets no ray through an edge.
rays_robust_cmd="$rays_cmd --embree-robust"
path_error_cmd="$bench path-error --width 128 --height 128 --max-depth 8 --reference-spp 4096 --spp 16,64,256 --budget 1 --noise-threshold 0.1,0.05 --cache-dir $out $shared/scenes/cornell.json"
sombra="$build/src/app/sombra"
alloc_cmd="LD_PRELOAD=$out/malloc_count.so $sombra render $shared/scenes/cornell.json --integrator path --max-depth 8 --width 64 --height 64 --spp N -q"

if want scenes; then
  echo "bench.sh: $scenes_cmd" >&2
  $scenes_cmd >"$out/scenes.md"
fi
if want load; then
  echo "bench.sh: $load_cmd" >&2
  $load_cmd >"$out/load.md"
fi
if want growth; then
  echo "bench.sh: $growth_cmd" >&2
  $growth_cmd >"$out/growth.md"
  echo "bench.sh: $growth_big_cmd" >&2
  $growth_big_cmd | tail -n +3 >>"$out/growth.md"  # its rows under the same header
  $plot_cmd
fi
if want path; then
  stamp="Run of $(date -u '+%Y-%m-%d %H:%M UTC'), load average at its start $(cut -d' ' -f1-3 /proc/loadavg), sombra commit $commit:"
  echo "bench.sh: $path_cmd" >&2
  { echo "$stamp"; echo; echo '```sh'; echo "$path_cmd"; echo '```'; echo; $path_cmd; } >"$out/path.md.tmp"
  mv "$out/path.md.tmp" "$out/path.md"
  echo "bench.sh: $rays_cmd" >&2
  { echo '```sh'; echo "$rays_cmd"; echo '```'; echo; $rays_cmd; } >"$out/path-rays.md.tmp"
  mv "$out/path-rays.md.tmp" "$out/path-rays.md"
  echo "bench.sh: $rays_robust_cmd" >&2
  { echo '```sh'; echo "$rays_robust_cmd"; echo '```'; echo; $rays_robust_cmd; } >"$out/path-rays-robust.md.tmp"
  mv "$out/path-rays-robust.md.tmp" "$out/path-rays-robust.md"
  echo "bench.sh: $path_error_cmd" >&2
  { echo '```sh'; echo "$path_error_cmd"; echo '```'; echo; $path_error_cmd; } >"$out/path-error.md.tmp"
  mv "$out/path-error.md.tmp" "$out/path-error.md"
  # Allocation calls (malloc, calloc, realloc, aligned) of a whole run of
  # sombra, counted by an LD_PRELOAD shim, at growing spp.
  cc -O2 -shared -fPIC -o "$out/malloc_count.so" bench/malloc_count.c
  {
    echo '```sh'
    echo "cc -O2 -shared -fPIC -o $out/malloc_count.so bench/malloc_count.c"
    echo "$alloc_cmd --stats-json $out/alloc.json -o $out/alloc.pfm   # N = 1, 4, 16, 64"
    echo '```'
    echo
    echo "| spp | rays (camera + shadow + bounce) | allocation calls, whole run |"
    echo "| ---: | ---: | ---: |"
    for spp in 1 4 16 64; do
      calls="$(LD_PRELOAD="$out/malloc_count.so" "$sombra" render "$shared/scenes/cornell.json" --integrator path --max-depth 8 \
        --width 64 --height 64 --spp "$spp" -q --stats-json "$out/alloc.json" -o "$out/alloc.pfm" 2>&1 >/dev/null |
        sed -n 's/^malloc_count: \([0-9]*\) allocation calls$/\1/p')"
      rays="$("$python" -c 'import json, sys; s = json.load(open(sys.argv[1])); print(sum(v for k, v in s.items() if k in ("camera_rays", "shadow_rays", "bounce_rays")))' "$out/alloc.json")"
      echo "| $spp | $rays | $calls |"
    done
  } >"$out/path-alloc.md.tmp"
  mv "$out/path-alloc.md.tmp" "$out/path-alloc.md"
fi

embree="$(dpkg-query -W -f='${Version}' libembree-dev 2>/dev/null || echo 'not installed')"
{
  echo "- Date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "- CPU: $(grep -m1 '^model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) cores available ($(grep -c '^processor' /proc/cpuinfo) logical CPUs)"
  echo "- Memory: $(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo); load average at the start: $load_at_start"
  echo "- Compiler: $(c++ --version | head -1); Release build; Embree (libembree-dev) $embree"
  echo "- sombra commit: $commit"
  echo
  echo '```sh'
  echo "tools/bench.sh   # runs, from the repository root:"
  echo "$scenes_cmd"
  echo "$load_cmd"
  echo "$growth_cmd"
  echo "$growth_big_cmd"
  echo "$plot_cmd"
  echo "$path_cmd"
  echo "$rays_cmd"
  echo "$rays_robust_cmd"
  echo "$path_error_cmd"
  echo '```'
} >"$out/machine.md.tmp"
if want scenes && want load && want growth && want path; then mv "$out/machine.md.tmp" "$out/machine.md"; fi

# Replace what lies between <!-- bench:NAME --> and <!-- /bench:NAME -->.
blocks=""
if want scenes && want load && want growth && want path; then blocks="machine"; fi
want scenes && blocks="$blocks scenes"
want load && blocks="$blocks load"
want growth && blocks="$blocks growth"
want path && blocks="$blocks path path-rays path-rays-robust path-error path-alloc"
"$python" - "$out" docs/performance.md $blocks <<'EOF'
import re, sys
out, doc = sys.argv[1], sys.argv[2]
text = open(doc).read()
for name in sys.argv[3:]:
    block = open(f"{out}/{name}.md").read().strip()
    pattern = re.compile(rf"(<!-- bench:{name} -->\n).*?(\n<!-- /bench:{name} -->)", re.S)
    if not pattern.search(text):
        sys.exit(f"{doc}: markers for '{name}' not found")
    text = pattern.sub(lambda m: m.group(1) + block + m.group(2), text)
open(doc, "w").write(text)
EOF
echo "bench.sh: wrote docs/performance.md and docs/performance-growth.png" >&2
