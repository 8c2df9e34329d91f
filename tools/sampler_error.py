#!/usr/bin/env python3
"""Error of `sombra render` against a `sombra-bench path-error` reference, over several seeds.

path-error measures one seed (0), and one image's MSE is itself noisy (a few
bright pixels carry much of it); comparing two samplers needs the mean over
seeds. For each scene, binary, spp and seed this renders the scene at the
reference's size with the path integrator (max depth 8) to a PFM, then
prints, per scene, binary and spp, the mean over seeds of
MSE = mean (x − r)² and relMSE = mean (x − r)² / (r² + 0.01) (over pixels
and channels, as path-error), with the standard error of that mean.

  tools/sampler_error.py --reference CACHE.bin --scene S.json \
      --binary old=/tmp/old/sombra --binary new=build/release/src/app/sombra \
      --spp 4,16,64 --seeds 1-8
"""
import argparse, math, os, struct, subprocess, sys, tempfile


def read_reference(path):
    data = open(path, "rb").read()
    w, h = struct.unpack("<ii", data[8:16])
    return w, h, struct.unpack("<%df" % (w * h * 3), data[16:16 + 12 * w * h])


def read_pfm(path):
    data = open(path, "rb").read()
    head = data.split(b"\n", 3)
    w, h = map(int, head[1].split())
    order = "<" if float(head[2]) < 0 else ">"
    v = struct.unpack(order + "%df" % (w * h * 3), head[3][:12 * w * h])
    rows = [v[3 * w * r:3 * w * (r + 1)] for r in range(h)]  # PFM rows run bottom to top
    return [x for row in reversed(rows) for x in row]


def errors(x, r):
    n = len(r)
    mse = sum((a - b) ** 2 for a, b in zip(x, r)) / n
    rel = sum((a - b) ** 2 / (b * b + 0.01) for a, b in zip(x, r)) / n
    return mse, rel


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--reference", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--binary", action="append", required=True, help="NAME=PATH")
    p.add_argument("--spp", default="4,16,64")
    p.add_argument("--seeds", default="1-8")
    a = p.parse_args()
    w, h, ref = read_reference(a.reference)
    lo, hi = map(int, a.seeds.split("-"))
    with tempfile.TemporaryDirectory() as tmp:
        for spp in map(int, a.spp.split(",")):
            for named in a.binary:
                name, binary = named.split("=", 1)
                mses, rels = [], []
                for seed in range(lo, hi + 1):
                    out = os.path.join(tmp, "x.pfm")
                    subprocess.run([binary, "render", a.scene, "--width", str(w), "--height", str(h), "--spp", str(spp),
                                    "--seed", str(seed), "--integrator", "path", "--max-depth", "8", "-q", "-o", out],
                                   check=True)
                    mse, rel = errors(read_pfm(out), ref)
                    mses.append(mse)
                    rels.append(rel)
                k = len(mses)
                def mean_se(v):
                    m = sum(v) / k
                    return m, math.sqrt(sum((x - m) ** 2 for x in v) / (k - 1) / k) if k > 1 else 0.0
                (m, ms), (r, rs) = mean_se(mses), mean_se(rels)
                print(f"{os.path.basename(a.scene)}\t{name}\t{spp}\tMSE {m:.4g} ± {ms:.2g}\trelMSE {r:.4g} ± {rs:.2g}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
