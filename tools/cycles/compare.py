#!/usr/bin/python3
"""Path-traced efficiency of sombra against Blender Cycles 3.4 (issue 21 §4).

Efficiency = 1 / (seconds × relMSE), relMSE = mean (x − r)² / (r² + 0.01)
over pixels and channels (as `sombra-bench path-error`), each renderer
against its own reference of --reference-spp samples, so that a small
difference in what the two converge to (reported as "references differ")
does not count as noise. The reference's own noise adds n/N of an n-spp
image's relMSE to the measured value; the figures are divided by
(1 + n/N) to remove it.

Seconds are each renderer's own share of the process: sombra's
`total_seconds` (load, build, render), and Cycles' render operator (scene
sync, BVH build, path tracing, writing its EXR), as timed by
tools/cycles/sombra_scene.py; Blender's start-up and OBJ import are left
out, and so are sombra's process start and image writing. Both renderers
run with the same thread count, seed by seed, interleaved, so that a
shared machine's drift hits both alike.

  tools/cycles/compare.py scenes/cornell-box-path.json --width 128 --height 128 \\
      --spp 16,64 --seeds 1-4 --threads 1 --cache /tmp/cycles-cache
"""
import argparse, json, math, os, subprocess, sys, tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from sampler_error import read_pfm  # noqa: E402


def rel_mse(x, r):
    return float(np.mean((x - r) ** 2 / (r * r + 0.01)))


def render_sombra(binary, scene, w, h, spp, seed, depth, threads, tmp):
    out, stats = os.path.join(tmp, "s.pfm"), os.path.join(tmp, "s.json")
    subprocess.run([binary, "render", scene, "--width", str(w), "--height", str(h), "--spp", str(spp), "--seed",
                    str(seed), "--integrator", "path", "--max-depth", str(depth), "--threads", str(threads), "-q",
                    "-o", out, "--stats-json", stats], check=True)
    image = np.array(read_pfm(out), dtype=np.float64).reshape(h, w, 3)
    return image, json.load(open(stats))["total_seconds"]


def render_cycles(blender, scene, w, h, spp, seed, depth, threads, tmp):
    out = os.path.join(tmp, "c.npy")
    subprocess.run([blender, "-b", "--factory-startup", "--python", os.path.join(HERE, "sombra_scene.py"), "--",
                    scene, "--width", str(w), "--height", str(h), "--spp", str(spp), "--seed", str(seed),
                    "--max-depth", str(depth), "--threads", str(threads), "--out", out],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return np.load(out).astype(np.float64), json.load(open(os.path.join(tmp, "c.json")))["render_seconds"]


def reference(kind, render, a, tmp):
    key = f"{os.path.basename(a.scene)}-{kind}-{a.width}x{a.height}-{a.reference_spp}-d{a.max_depth}.npy"
    path = os.path.join(a.cache, key)
    if not os.path.exists(path):
        image, seconds = render(a.scene, a.width, a.height, a.reference_spp, 1000, a.max_depth, 0, tmp)
        np.save(path, image)
        print(f"# {kind} reference: {a.reference_spp} spp in {seconds:.1f} s", flush=True)
    return np.load(path)


def mean_se(values):
    k = len(values)
    m = sum(values) / k
    return m, (math.sqrt(sum((x - m) ** 2 for x in values) / (k - 1) / k) if k > 1 else 0.0)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("scene")
    p.add_argument("--width", type=int, default=128)
    p.add_argument("--height", type=int, default=128)
    p.add_argument("--spp", default="16,64")
    p.add_argument("--seeds", default="1-4")
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--reference-spp", type=int, default=4096)
    p.add_argument("--cache", default="/tmp/cycles-cache")
    p.add_argument("--sombra", default=os.path.join(os.path.dirname(os.path.dirname(HERE)),
                                                    "build/release/src/app/sombra"))
    p.add_argument("--blender", default="blender")
    a = p.parse_args()
    os.makedirs(a.cache, exist_ok=True)
    sombra = lambda *args: render_sombra(a.sombra, *args)  # noqa: E731
    cycles = lambda *args: render_cycles(a.blender, *args)  # noqa: E731
    lo, hi = map(int, a.seeds.split("-"))
    with tempfile.TemporaryDirectory() as tmp:
        refs = {"sombra": reference("sombra", sombra, a, tmp), "cycles": reference("cycles", cycles, a, tmp)}
        print(f"{os.path.basename(a.scene)}, {a.width}x{a.height}, max depth {a.max_depth}, {a.threads} thread(s), "
              f"seeds {lo}-{hi}, references of {a.reference_spp} spp; references differ by relMSE "
              f"{rel_mse(refs['sombra'], refs['cycles']):.3g}, means "
              f"{refs['sombra'].mean():.4f} (sombra) {refs['cycles'].mean():.4f} (Cycles)")
        print("| spp | sombra s | sombra relMSE | Cycles s | Cycles relMSE | relMSE × s sombra ÷ Cycles |")
        print("| ---: | ---: | ---: | ---: | ---: | ---: |")
        for spp in map(int, a.spp.split(",")):
            runs = {"sombra": ([], []), "cycles": ([], [])}
            for seed in range(lo, hi + 1):
                for name, render in (("sombra", sombra), ("cycles", cycles)):
                    image, seconds = render(a.scene, a.width, a.height, spp, seed, a.max_depth, a.threads, tmp)
                    runs[name][0].append(seconds)
                    runs[name][1].append(rel_mse(image, refs[name]) / (1 + spp / a.reference_spp))
            row = {name: (mean_se(s)[0], *mean_se(e)) for name, (s, e) in runs.items()}
            (ss, se, se_se), (cs, ce, ce_se) = row["sombra"], row["cycles"]
            print(f"| {spp} | {ss:.3f} | {se:.4g} ± {se_se:.2g} | {cs:.3f} | {ce:.4g} ± {ce_se:.2g} | "
                  f"{(ss * se) / (cs * ce):.3f} |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
