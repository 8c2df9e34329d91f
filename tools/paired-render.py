#!/usr/bin/env python3
"""Paired timings of `sombra render` configurations, one process per render.

Each round runs every configuration once, the order rotated and reversed
from round to round so that drift in a shared machine's speed hits all of
them alike; build_seconds and render_seconds come from --stats-json. For
every configuration after the first the figure is the median over rounds of
its time divided by the first's in the same round (so above 1: slower than
the first), with the spread of those ratios, for build, render and
build + render; plus the medians of the seconds themselves and the
structure's size. The load average is printed at the start and the end.

    tools/paired-render.py --rounds 10 --scene ../shared/scenes/dragon.json \\
        --config "old=/tmp/sombra-old --accel bvh" \\
        --config "new=build/release/src/app/sombra --accel bvh" \\
        --config "embree=build/release/src/app/sombra --accel embree" \\
        -- --integrator path --spp 16 --threads 2

A configuration is LABEL=BINARY [ARG ...]: a sombra binary and the options
only it gets; arguments after -- go to every render. Giving the same
binary and options twice under two labels is an A/A check of the noise.
"""
import argparse
import json
import os
import shlex
import statistics
import subprocess
import sys
import tempfile


def run_once(command, scene, extra, tmp):
    stats = os.path.join(tmp, "stats.json")
    cmd = [command[0], "render", scene] + command[1:] + ["-q", "--stats-json", stats,
                                                         "-o", os.path.join(tmp, "out.pfm")] + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(stats) as f:
        s = json.load(f)
    return s["build_seconds"], s["render_seconds"], s["accel_bytes"]


def spread(values):
    return f"{statistics.median(values):.3f} ({min(values):.2f}-{max(values):.2f})"


def load():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", required=True)
    p.add_argument("--config", action="append", required=True,
                   help="LABEL=BINARY [ARG ...]; the first is the reference")
    p.add_argument("--rounds", type=int, default=10)
    p.add_argument("extra", nargs="*", help="arguments for every render (after --)")
    a = p.parse_args()
    configs = []
    for c in a.config:
        label, _, command = c.partition("=")
        if not label or not command:
            p.error(f"--config {c!r}: expected LABEL=BINARY [ARG ...]")
        configs.append((label, shlex.split(command)))
    labels = [c[0] for c in configs]
    if len(set(labels)) != len(labels):
        p.error("labels must differ")
    print(f"load at start: {load()}", file=sys.stderr)
    start_load = load()
    times = {label: [] for label in labels}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            order = configs[r % len(configs):] + configs[:r % len(configs)]
            if r % 2 == 1:
                order.reverse()
            for label, command in order:
                times[label].append(run_once(command, a.scene, a.extra, tmp))
    print(f"scene {a.scene}, {a.rounds} rounds, common arguments {a.extra}; load {start_load} at the start, "
          f"{load()} at the end")
    print("| config | build s | render s | MB | build ÷ first | render ÷ first | build+render ÷ first |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    ref = times[labels[0]]
    for label in labels:
        t = times[label]
        row = (f"| {label} | {statistics.median(x[0] for x in t):.4f} | {statistics.median(x[1] for x in t):.4f} "
               f"| {t[0][2] / 1e6:.1f} |")
        if label == labels[0]:
            row += " 1 | 1 | 1 |"
        else:
            rb = [x[0] / y[0] for x, y in zip(t, ref)]
            rr = [x[1] / y[1] for x, y in zip(t, ref)]
            rs = [(x[0] + x[1]) / (y[0] + y[1]) for x, y in zip(t, ref)]
            row += f" {spread(rb)} | {spread(rr)} | {spread(rs)} |"
        print(row)


if __name__ == "__main__":
    main()
