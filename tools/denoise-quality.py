#!/usr/bin/python3
"""The denoiser's quality table (docs/performance.md, "The denoiser").

For each scene: a converged reference (cached), raw renders at 16, 64 and
128 spp, the 16-spp render denoised, and a raw and a denoised --time render
as long as the whole denoised 16-spp command took. Prints relative MSE, mean((x - ref)^2 /
(ref^2 + 0.01)), and seconds, as a Markdown table, and how well the
denoised image keeps the light (its mean over the raw image's, whole and
per quarter). With --seeds N the denoised 16-spp and raw --time renders
are made with seeds 1..N and their errors and seconds averaged (a raw
render's error at 16-128 spp rests on a few fireflies: one seed's ratio
can be off by 20 %); the last column is then their ratio.

  tools/denoise-quality.py SOMBRA OUTDIR [--ref-spp 2048] [--seeds N] SCENE.json:WxH ...
"""
import argparse
import os
import subprocess
import sys
import time

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3 if kind == b"PF" else 1)[::-1].astype(np.float64)


def rel_mse(image, ref):
    return float(np.mean((image - ref) ** 2 / (ref**2 + 0.01)))


def render(sombra, scene, size, out, *options):
    w, h = size
    start = time.monotonic()
    subprocess.run([sombra, "render", scene, "--width", str(w), "--height", str(h), "-q", "-o", out, *options],
                   check=True)
    return time.monotonic() - start


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("sombra")
    parser.add_argument("outdir")
    parser.add_argument("--ref-spp", type=int, default=2048)
    parser.add_argument("--seeds", type=int, default=0, help="average the equal-time figures over seeds 1..N")
    parser.add_argument("scenes", nargs="+", help="SCENE.json:WIDTHxHEIGHT")
    args = parser.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    print("| scene | size | raw 16 | raw 64 | raw 128 | denoised 16 | seconds (denoised 16) "
          "| raw, same seconds | denoised, same seconds | kept (image, worst quarter) |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for item in args.scenes:
        scene, size_text = item.rsplit(":", 1)
        size = tuple(int(v) for v in size_text.split("x"))
        name = os.path.splitext(os.path.basename(scene))[0]
        path = lambda tag: os.path.join(args.outdir, f"{name}-{tag}.pfm")
        if not os.path.exists(path("ref")):
            render(args.sombra, scene, size, path("ref"), "--spp", str(args.ref_spp), "--seed", "99")
        ref = read_pfm(path("ref"))
        raw = {}
        for spp in (16, 64, 128):
            render(args.sombra, scene, size, path(f"raw{spp}"), "--spp", str(spp))
            raw[spp] = rel_mse(read_pfm(path(f"raw{spp}")), ref)
        seconds = render(args.sombra, scene, size, path("den16"), "--spp", "16", "--denoise")
        denoised = read_pfm(path("den16"))
        render(args.sombra, scene, size, path("time"), "--time", f"{seconds:.3f}")
        same_time = rel_mse(read_pfm(path("time")), ref)
        render(args.sombra, scene, size, path("time-den"), "--time", f"{seconds:.3f}", "--denoise")
        same_time_denoised = rel_mse(read_pfm(path("time-den")), ref)
        noisy = read_pfm(path("raw16"))
        h, w = noisy.shape[:2]
        ratios = [denoised.mean() / noisy.mean()]
        for ys in (slice(0, h // 2), slice(h // 2, h)):
            for xs in (slice(0, w // 2), slice(w // 2, w)):
                ratios.append(denoised[ys, xs].mean() / max(noisy[ys, xs].mean(), 1e-12))
        worst = max(ratios[1:], key=lambda r: abs(r - 1))
        print(f"| {name} | {w}×{h} | {raw[16]:.4f} | {raw[64]:.4f} | {raw[128]:.4f} | "
              f"{rel_mse(denoised, ref):.4f} | {seconds:.1f} | {same_time:.4f} | {same_time_denoised:.4f} | "
              f"{ratios[0]:.4f}, {worst:.4f} |",
              flush=True)
        if args.seeds > 0:
            errors, raw_errors, times = [], [], []
            for seed in range(1, args.seeds + 1):
                t = render(args.sombra, scene, size, path("seeded"), "--spp", "16", "--denoise", "--seed", str(seed))
                errors.append(rel_mse(read_pfm(path("seeded")), ref))
                render(args.sombra, scene, size, path("seeded-time"), "--time", f"{t:.3f}", "--seed", str(seed))
                raw_errors.append(rel_mse(read_pfm(path("seeded-time")), ref))
                times.append(t)
            print(f"|   seeds 1–{args.seeds}: denoised 16 {np.mean(errors):.5f} ({min(errors):.5f}–{max(errors):.5f}), "
                  f"{np.mean(times):.2f} s; raw, same seconds {np.mean(raw_errors):.5f} "
                  f"({min(raw_errors):.5f}–{max(raw_errors):.5f}); ratio {np.mean(errors) / np.mean(raw_errors):.3f} |",
                  flush=True)


if __name__ == "__main__":
    sys.exit(main())
