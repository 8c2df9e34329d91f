#!/usr/bin/python3
"""docs/gallery/blender-glass-clearcoat.png: a scene made and exported by
Blender 3.4, rendered by sombra from the exported glTF (left) and by Cycles
from Blender's own scene (right), at the same samples per pixel (issue 24).

  tools/cycles/gallery.py [--spp 256] [--out docs/gallery/blender-glass-clearcoat.png]

Needs Debian's `blender` package (not installed by tools/install-deps.sh:
only this gallery and tools/cycles/compare.py use it).
"""
import argparse, os, subprocess, sys, tempfile

import numpy as np
from PIL import Image, ImageDraw

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
from sampler_error import read_pfm  # noqa: E402


def srgb8(linear):
    x = np.clip(linear, 0, 1)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)
    return Image.fromarray((x * 255 + 0.5).astype(np.uint8))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--out", default=os.path.join(ROOT, "docs/gallery/blender-glass-clearcoat.png"))
    p.add_argument("--sombra", default=os.path.join(ROOT, "build/release/src/app/sombra"))
    p.add_argument("--keep", help="a folder to keep the glTF, the scene file and both renders in")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = a.keep or tmp
        subprocess.run(["blender", "-b", "--factory-startup", "--python", os.path.join(HERE, "glass_clearcoat_scene.py"),
                        "--", work, "--spp", str(a.spp)], check=True, stdout=subprocess.DEVNULL)
        pfm = os.path.join(work, "sombra.pfm")
        subprocess.run([a.sombra, "render", os.path.join(work, "scene.json"), "-q", "-o", pfm], check=True)
        cycles = np.load(os.path.join(work, "cycles.npy"))
        h, w, _ = cycles.shape
        sombra = np.array(read_pfm(pfm), dtype=np.float32).reshape(h, w, 3)
    side = Image.new("RGB", (2 * w, h))
    for i, (image, label) in enumerate(((sombra, "sombra (Blender's glTF export)"), (cycles, "Cycles (the .blend)"))):
        side.paste(srgb8(image), (i * w, 0))
        ImageDraw.Draw(side).text((i * w + 10, h - 22), f"{label}, {a.spp} spp", fill=(255, 255, 255))
    side.save(a.out)
    print(f"wrote {a.out}; mean linear RGB sombra {sombra.mean(axis=(0, 1))}, Cycles {cycles.mean(axis=(0, 1))}")


if __name__ == "__main__":
    sys.exit(main())
