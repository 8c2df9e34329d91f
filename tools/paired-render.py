#!/usr/bin/env python3
"""Paired timings of `sombra render` configurations, one process per render.

Each round runs every configuration once, the order rotated and reversed
from round to round so that drift in a shared machine's speed hits all of
them alike; build_seconds and render_seconds come from --stats-json. For
every configuration after the first the figure is the median over rounds of
its time divided by the first's in the same round (so above 1: slower than
the first), with the spread of those ratios, for build, render and
build + render; plus the medians of the seconds themselves and the
structure's bytes. The load average is printed at the start and the end.

    tools/paired-render.py --rounds 10 --scene ../shared/scenes/dragon.json \\
        --config "embree:fast" --config "bvh:fast" --config "bvh:high" -- --threads 2

A configuration is ACCEL:QUALITY (--accel, --build-quality); arguments after
-- go to every render.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def run_once(sombra, scene, accel, quality, extra, tmp):
    stats = os.path.join(tmp, "stats.json")
    cmd = [sombra, "render", scene, "--accel", accel, "--build-quality", quality, "-q",
           "--stats-json", stats, "-o", os.path.join(tmp, "out.pfm")] + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(stats) as f:
        s = json.load(f)
    return s["build_seconds"], s["render_seconds"], s["accel_bytes"]


def spread(values):
    return f"{statistics.median(values):.3f} ({min(values):.2f}-{max(values):.2f})"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--sombra", default="build/release/src/app/sombra")
    p.add_argument("--scene", required=True)
    p.add_argument("--config", action="append", required=True, help="ACCEL:QUALITY, the first is the reference")
    p.add_argument("--rounds", type=int, default=10)
    p.add_argument("extra", nargs="*", help="arguments for every render (after --)")
    a = p.parse_args()
    configs = [tuple(c.split(":")) for c in a.config]
    print(f"load at start: {open('/proc/loadavg').read().split()[:3]}", file=sys.stderr)
    times = {c: [] for c in configs}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            order = configs[r % len(configs):] + configs[:r % len(configs)]
            if r % 2 == 1:
                order.reverse()
            for c in order:
                times[c].append(run_once(a.sombra, a.scene, c[0], c[1], a.extra, tmp))
    load_end = open('/proc/loadavg').read().split()[:3]
    ref = configs[0]
    print(f"scene {a.scene}, {a.rounds} rounds, extra args {a.extra}; load at end {load_end}")
    print("| config | build s | render s | MB | build ÷ ref | render ÷ ref | build+render ÷ ref |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for c in configs:
        t = times[c]
        b = [x[0] for x in t]
        rnd = [x[1] for x in t]
        row = f"| {c[0]}:{c[1]} | {statistics.median(b):.4f} | {statistics.median(rnd):.4f} | {t[0][2] / 1e6:.1f} |"
        if c == ref:
            row += " 1 | 1 | 1 |"
        else:
            rt = times[ref]
            rb = [x[0] / y[0] for x, y in zip(t, rt)]
            rr = [x[1] / y[1] for x, y in zip(t, rt)]
            rs = [(x[0] + x[1]) / (y[0] + y[1]) for x, y in zip(t, rt)]
            row += f" {spread(rb)} | {spread(rr)} | {spread(rs)} |"
        print(row)


if __name__ == "__main__":
    main()
