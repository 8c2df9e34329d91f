#!/usr/bin/python3
"""The denoiser's gallery pictures (docs/gallery/denoise-*.png).

From the PFM images tools/denoise-quality.py leaves in OUTDIR
(NAME-raw16.pfm, NAME-den16.pfm, NAME-ref.pfm) it makes, per scene,
denoise-NAME.png: the noisy 16-spp render, the same denoised and the
reference, with a white gap between them, side by side for the square
Cornell box and one above the other for the wide scenes; and
denoise-crops.png: 3x-enlarged crops of texture edges (textured) and a
shadow boundary (Cornell box), noisy / denoised / reference. Pixels are
encoded as sombra's PNG writer does: clamped to [0, 1], sRGB, 8 bits.

  tools/denoise-gallery.py OUTDIR GALLERYDIR
"""
import argparse
import importlib.util
import os
import struct
import sys
import zlib

import numpy as np

SCENES = ("cornell-box-path", "pbr-spheres", "textured", "dragon-glass")
SIDE_BY_SIDE = {"cornell-box-path"}
TAGS = ("raw16", "den16", "ref")  # noisy, denoised, reference
STRIP_GAP = 4
# (scene, left column, top row) of each 120x80 crop, rows counted from the top
CROPS = (("textured", 50, 60), ("cornell-box-path", 110, 150))
CROP_SIZE = (120, 80)
CROP_ZOOM = 3
CROP_GAP = 6


def load_read_pfm():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "denoise-quality.py")
    spec = importlib.util.spec_from_file_location("denoise_quality", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.read_pfm


def to_srgb8(linear):
    x = np.clip(linear, 0.0, 1.0)
    encoded = np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)
    return np.round(encoded * 255).astype(np.uint8)


def write_png(path, rgb):
    height, width = rgb.shape[:2]
    rows = b"".join(b"\0" + rgb[y].tobytes() for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(rows, 9)))
        f.write(chunk(b"IEND", b""))


def join(images, gap, axis):
    """Images along axis (0: stacked, 1: side by side) with white gaps."""
    shape = list(images[0].shape)
    shape[axis] = gap
    white = np.full(shape, 255, dtype=np.uint8)
    parts = [images[0]]
    for image in images[1:]:
        parts += [white, image]
    return np.concatenate(parts, axis=axis)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("outdir", help="folder with NAME-raw16.pfm, NAME-den16.pfm, NAME-ref.pfm")
    parser.add_argument("gallerydir")
    args = parser.parse_args()
    read_pfm = load_read_pfm()
    images = {name: [to_srgb8(read_pfm(os.path.join(args.outdir, f"{name}-{tag}.pfm"))) for tag in TAGS]
              for name in SCENES}
    for name in SCENES:
        strip = join(images[name], STRIP_GAP, 1 if name in SIDE_BY_SIDE else 0)
        write_png(os.path.join(args.gallerydir, f"denoise-{name}.png"), strip)
    width, height = CROP_SIZE
    rows = []
    for name, left, top in CROPS:
        crops = [image[top:top + height, left:left + width].repeat(CROP_ZOOM, 0).repeat(CROP_ZOOM, 1)
                 for image in images[name]]
        rows.append(join(crops, CROP_GAP, 1))
    write_png(os.path.join(args.gallerydir, "denoise-crops.png"), join(rows, CROP_GAP, 0))


if __name__ == "__main__":
    sys.exit(main())
