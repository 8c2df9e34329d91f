#!/usr/bin/env python3
"""Plots the cost-growth CSV of `sombra-bench growth --csv` as a PNG.

    python3 tools/plot-growth.py growth.csv [more.csv ...] docs/performance-growth.png

Three log-log panels against triangle count: build seconds, render seconds,
structure megabytes, one line per backend, each with a dotted line of slope 1
(linear growth) through its first point for comparison. Several CSVs (runs
of separate processes, e.g. the largest mesh on its own) are plotted as one
series per backend. Needs matplotlib
(Debian python3-matplotlib).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

PANELS = [
    ("build_seconds", "build time (s)", 1.0),
    ("render_seconds", "render time (s)", 1.0),
    ("accel_bytes", "structure size (MB)", 1e-6),
]
COLOURS = {"bvh": "#c0392b", "embree": "#2c3e50"}


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__.strip().split("\n\n")[1])
    series = {}
    for path in sys.argv[1:-1]:
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                series.setdefault(row["accel"], []).append(row)

    fig, axes = plt.subplots(1, len(PANELS), figsize=(13, 4.2), dpi=110)
    for ax, (column, label, scale) in zip(axes, PANELS):
        for accel, rows in series.items():
            rows = sorted(rows, key=lambda r: int(r["triangles"]))
            x = [int(r["triangles"]) for r in rows]
            y = [float(r[column]) * scale for r in rows]
            colour = COLOURS.get(accel, None)
            ax.plot(x, y, "o-", color=colour, label=accel)
            ax.plot([x[0], x[-1]], [y[0], y[0] * x[-1] / x[0]], ":", color=colour, linewidth=1,
                    label=f"{accel}, linear from the first point")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles")
        ax.set_title(label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("sombra: cost against triangle count (Stanford dragon and its subdivisions, to 105 M triangles)")
    fig.tight_layout()
    fig.savefig(sys.argv[-1])


if __name__ == "__main__":
    main()
