#!/usr/bin/env python3
"""Writes the small textures of scenes/textured.json into scenes/textures/.

    tools/make-textures.py [OUT_FOLDER]     (default: scenes/textures)

All are 64x64 PNGs (the screen 256x256), computed here (numpy + Pillow), so that the repository
holds nothing copied from elsewhere:
  checker.png   8x8 checkerboard, colour (sRGB)
  sign.png      an arrow pointing up beside the letter F: tells up from down
                and left from right at a glance
  tiles-normal.png  tangent-space normal map (OpenGL convention: +y toward
                increasing v, the image's top) of 4x4 bevelled tiles, 16 bit
  rough.png     roughness stripes (grey, data), 0.1 to 0.6
  screen.png    a perforated screen, RGBA: painted metal (sRGB colour) with
                alpha 0 in a 4x4 grid of round holes (a cut-out, spec §12)
The committed files were made by this script; run it to check or remake them.
"""
import sys
from pathlib import Path

import numpy as np
from PIL import Image

N = 64


def save_rgb8(path, rgb):
    Image.fromarray(np.clip(np.round(rgb * 255), 0, 255).astype(np.uint8), "RGB").save(path, optimize=True)


def checker():
    y, x = np.mgrid[0:N, 0:N]
    dark = ((x // 8) + (y // 8)) % 2 == 1
    rgb = np.empty((N, N, 3))
    rgb[...] = (0.85, 0.78, 0.62)
    rgb[dark] = (0.22, 0.27, 0.33)
    return rgb


def sign():
    rgb = np.empty((N, N, 3))
    rgb[...] = (0.9, 0.88, 0.8)
    # An arrow pointing up (row 0 is the image's top) on the left half...
    for row in range(8, 30):
        half = (row - 8) // 2
        rgb[row, 16 - half:17 + half] = (0.75, 0.1, 0.08)
    rgb[30:56, 13:20] = (0.75, 0.1, 0.08)
    # ... and an F on the right half.
    rgb[8:56, 38:44] = (0.1, 0.15, 0.45)
    rgb[8:14, 38:58] = (0.1, 0.15, 0.45)
    rgb[28:34, 38:54] = (0.1, 0.15, 0.45)
    return rgb


def tiles_normal():
    # Height: 1 inside each 16x16 tile, falling to 0 over a 4-texel bevel.
    t = (np.arange(N) % 16) + 0.5
    edge = np.minimum(t, 16 - t)
    ramp = np.clip(edge / 4.0, 0, 1)
    height = np.minimum.outer(ramp, ramp) * 2.0  # rows (from the top), columns
    # Slopes per texel: +x to the right, +y up (toward the image's top row).
    dh_dx = np.gradient(height, axis=1)
    dh_dy = -np.gradient(height, axis=0)
    n = np.stack([-dh_dx, -dh_dy, np.ones_like(height)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    encoded = np.round((n + 1) * 0.5 * 65535).astype(">u2")
    # Pillow writes 16-bit RGB PNGs only through raw data: build the file by hand.
    import struct
    import zlib
    raw = b"".join(b"\x00" + encoded[row].tobytes() for row in range(N))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", N, N, 16, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def rough():
    x = np.arange(N)
    stripes = np.where((x // 8) % 2 == 0, 0.1, 0.6)
    grey = np.tile(stripes, (N, 1))
    return np.clip(np.round(grey * 255), 0, 255).astype(np.uint8)


def screen():
    side = 4 * N  # fine enough that bilinear alpha draws round holes
    y, x = np.mgrid[0:side, 0:side] + 0.5
    # Round holes of radius 22 texels centred in each 64x64 cell.
    cx, cy = x % 64 - 32, y % 64 - 32
    hole = cx * cx + cy * cy < 22.0 * 22.0
    rgba = np.empty((side, side, 4))
    rgba[...] = (0.18, 0.42, 0.36, 1.0)
    rgba[hole, 3] = 0.0
    return Image.fromarray(np.round(rgba * 255).astype(np.uint8), "RGBA")


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "scenes" / "textures"
    out.mkdir(parents=True, exist_ok=True)
    save_rgb8(out / "checker.png", checker())
    save_rgb8(out / "sign.png", sign())
    (out / "tiles-normal.png").write_bytes(tiles_normal())
    Image.fromarray(rough(), "L").save(out / "rough.png", optimize=True)
    screen().save(out / "screen.png", optimize=True)
    print("wrote", ", ".join(sorted(p.name for p in out.glob("*.png"))), "in", out)


if __name__ == "__main__":
    main()
