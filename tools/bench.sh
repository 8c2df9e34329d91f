#!/usr/bin/env bash
# Runs sombra-bench and rewrites the measured parts of docs/performance.md:
# the machine, the date and the exact commands; the bvh-against-embree table
# over ../shared/scenes; OBJ loading against tinyobjloader; and cost growth
# from the dragon's resolutions up to a 13.9 M-triangle subdivision, with its
# plot (docs/performance-growth.png). Everything else in that file is prose
# and stays as it is. Takes about 5 minutes on 2 cores; run it on a quiet
# machine (the load average at the start is recorded).
#
#   tools/bench.sh            # all of it
#   SOMBRA_BENCH_REPS=1 tools/bench.sh   # a quick run (fewer rounds)
#   SOMBRA_BENCH_BUILD=build-x tools/bench.sh   # another build folder
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
reps="${SOMBRA_BENCH_REPS:-5}"
growth_reps="${SOMBRA_BENCH_GROWTH_REPS:-3}"
build="${SOMBRA_BENCH_BUILD:-build/release}"  # relative to the repository root
out="build/bench"
shared="../shared"
# Debian's python3, where python3-numpy and python3-matplotlib live (a
# python3 earlier on PATH, e.g. from pyenv, may not have them).
python="${SOMBRA_PYTHON:-/usr/bin/python3}"

"$root/tools/install-deps.sh"
[ -d "$shared/scenes" ] || { echo "bench.sh: $root/$shared/scenes not found" >&2; exit 1; }
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target sombra-bench -j "$(nproc)"
mkdir -p "$out"

load_at_start="$(cut -d' ' -f1-3 /proc/loadavg)"
[ -f build/bench-meshes/dragon-sub2.ply ] || "$python" tools/make-big-mesh.py --levels 2

bench="$build/bench/sombra-bench"
scenes_cmd="$bench scenes --reps $reps $shared/scenes/bunny.json $shared/scenes/dragon.json $shared/scenes/manylights.json $shared/scenes/cornell.json $shared/scenes/phong.json"
load_cmd="$bench load --reps $reps $shared/models/dragon.obj"
growth_cmd="$bench growth --reps $growth_reps --csv $out/growth.csv $shared/models/dragon-res2.obj $shared/models/dragon.ply build/bench-meshes/dragon-sub1.ply build/bench-meshes/dragon-sub2.ply"
plot_cmd="$python tools/plot-growth.py $out/growth.csv docs/performance-growth.png"

echo "bench.sh: $scenes_cmd" >&2
$scenes_cmd >"$out/scenes.md"
echo "bench.sh: $load_cmd" >&2
$load_cmd >"$out/load.md"
echo "bench.sh: $growth_cmd" >&2
$growth_cmd >"$out/growth.md"
$plot_cmd

commit="$(git rev-parse --short HEAD)"
git diff --quiet HEAD -- src bench CMakeLists.txt || commit="$commit + uncommitted changes"
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
  echo "$plot_cmd"
  echo '```'
} >"$out/machine.md"

# Replace what lies between <!-- bench:NAME --> and <!-- /bench:NAME -->.
"$python" - "$out" docs/performance.md <<'EOF'
import re, sys
out, doc = sys.argv[1], sys.argv[2]
text = open(doc).read()
for name in ("machine", "scenes", "load", "growth"):
    block = open(f"{out}/{name}.md").read().strip()
    pattern = re.compile(rf"(<!-- bench:{name} -->\n).*?(\n<!-- /bench:{name} -->)", re.S)
    if not pattern.search(text):
        sys.exit(f"{doc}: markers for '{name}' not found")
    text = pattern.sub(lambda m: m.group(1) + block + m.group(2), text)
open(doc, "w").write(text)
EOF
echo "bench.sh: wrote docs/performance.md and docs/performance-growth.png" >&2
