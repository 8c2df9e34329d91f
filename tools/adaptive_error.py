#!/usr/bin/env python3
"""Error and efficiency of `sombra render` configurations against a
`sombra-bench path-error` reference, over several seeds (issue 21 §2:
adaptive against uniform sampling at equal time).

For each configuration (LABEL=OPTIONS, e.g. "uniform 64=--spp 64" or
"T 0.05=--spp 256 --noise-threshold 0.05") and seed, this renders the scene
at the reference's size with the path integrator (max depth 8) to a PFM
with --stats-json, the configurations interleaved seed by seed so that a
shared machine's drift hits them alike. It prints, per configuration, the
means over seeds of the samples per pixel reached, the render seconds,
relMSE = mean (x − r)² / (r² + 0.01) (over pixels and channels, as
path-error) with its standard error, and relMSE × render seconds: inverse
efficiency, lower is better; equal across uniform spp for an unbiased
estimator, so comparing it is comparing at equal time.

  tools/adaptive_error.py --reference CACHE.bin --scene S.json \\
      --binary new=build/release/src/app/sombra --binary old=/tmp/old/sombra --seeds 1-4 \\
      --config "uniform 64=--spp 64" --config "T 0.05=--spp 256 --noise-threshold 0.05"
"""
import argparse, json, math, os, shlex, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sampler_error import errors, read_pfm, read_reference  # noqa: E402


def mean_se(values):
    k = len(values)
    m = sum(values) / k
    return m, (math.sqrt(sum((x - m) ** 2 for x in values) / (k - 1) / k) if k > 1 else 0.0)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--reference", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--binary", action="append", required=True,
                   help="PATH, or NAME=PATH given more than once: every configuration runs with each")
    p.add_argument("--config", action="append", required=True, help="LABEL=OPTIONS")
    p.add_argument("--seeds", default="1-4")
    p.add_argument("--threads", default="0")
    a = p.parse_args()
    w, h, ref = read_reference(a.reference)
    lo, hi = map(int, a.seeds.split("-"))
    binaries = [b.split("=", 1) if "=" in b else ["", b] for b in a.binary]
    configs = [((name + " " if name else "") + label, binary, options)
               for label, options in (c.split("=", 1) for c in a.config) for name, binary in binaries]
    results = {label: {"spp": [], "seconds": [], "rel": []} for label, _, _ in configs}
    with tempfile.TemporaryDirectory() as tmp:
        out, stats = os.path.join(tmp, "x.pfm"), os.path.join(tmp, "s.json")
        for seed in range(lo, hi + 1):
            for label, binary, options in configs:
                subprocess.run([binary, "render", a.scene, "--width", str(w), "--height", str(h), "--seed", str(seed),
                                "--integrator", "path", "--max-depth", "8", "--threads", a.threads, "-q", "-o", out,
                                "--stats-json", stats] + shlex.split(options), check=True)
                s = json.load(open(stats))
                r = results[label]
                r["spp"].append(s.get("spp_reached", s["spp"]))  # binaries before §18 have no spp_reached
                r["seconds"].append(s["render_seconds"])
                r["rel"].append(errors(read_pfm(out), ref)[1])
    print(f"{os.path.basename(a.scene)}, {w}x{h}, seeds {lo}-{hi}")
    print("| configuration | spp reached | render s | relMSE | relMSE × s |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for label, _, _ in configs:
        r = results[label]
        spp, seconds = mean_se(r["spp"])[0], mean_se(r["seconds"])[0]
        rel, rel_se = mean_se(r["rel"])
        print(f"| {label} | {spp:.1f} | {seconds:.3f} | {rel:.4g} ± {rel_se:.2g} | {rel * seconds:.4g} |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
