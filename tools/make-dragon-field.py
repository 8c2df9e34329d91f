#!/usr/bin/python3
"""Writes a scene of a field of Stanford dragons for the instancing benchmark
(docs/performance.md, "Instancing") and the gallery's dragon field: N dragons
on a jittered square grid, each turned by a random yaw, scaled by 0.85-1.15,
one in eight mirrored, on a floor, seen from one corner across the field, lit
by a low sun and a sky.

The dragons are one object with an "instances" list (spec §23: the mesh is
stored once); with --flatten each dragon is an object of its own (stored once
per dragon: the comparison that only fits for small fields). Deterministic
(fixed seed): the same N gives the same placements either way.

  /usr/bin/python3 tools/make-dragon-field.py --count 10000 -o /tmp/field/dragon-field.json
  /usr/bin/python3 tools/make-dragon-field.py --count 25 --flatten -o /tmp/field/flat-25.json

--model picks another mesh (e.g. the bunny for the flattening-rule runs);
--base gives its own transform list (JSON) that sets it on the floor at
about the dragon's size. Paths in the scene are relative to its folder.
"""
import argparse
import json
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "models"))
# dragon.ply (871,414 triangles; the OBJ holds the same geometry, slower to
# read) is about 0.155 wide: scale 10 and this shift stand it on y = 0 near
# the origin, as scenes/dragon-glass.json does.
DRAGON_BASE = [{"scale": 10}, {"translate": [0.0586, -0.5273, 0.046]}]


def placements(count, spacing, rng):
    """One transform list per dragon, row by row on a jittered grid."""
    side = math.ceil(math.sqrt(count))
    half = 0.5 * (side - 1) * spacing
    out = []
    for k in range(count):
        i, j = divmod(k, side)
        x = -half + j * spacing + rng.uniform(-0.3, 0.3) * spacing
        z = -half + i * spacing + rng.uniform(-0.3, 0.3) * spacing
        yaw = rng.uniform(0.0, 360.0)
        s = round(rng.uniform(0.85, 1.15), 4)
        mirrored = rng.random() < 0.125
        out.append([
            {"scale": [-s if mirrored else s, s, s]},
            {"rotate": {"axis": [0, 1, 0], "degrees": round(yaw, 3)}},
            {"translate": [round(x, 4), 0, round(z, 4)]},
        ])
    return out, half


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--count", type=int, default=10000)
    ap.add_argument("--flatten", action="store_true", help="one object per dragon instead of instances")
    ap.add_argument("--model", default=os.path.join(SHARED, "dragon.ply"))
    ap.add_argument("--base", default=None, help="the model's own transform list, JSON")
    ap.add_argument("--spacing", type=float, default=2.2)
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=360)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--integrator", choices=["direct", "path"], default="direct")
    ap.add_argument("--seed", type=int, default=20261127)
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()

    rng = random.Random(args.seed)
    field, half = placements(args.count, args.spacing, rng)
    out_dir = os.path.dirname(os.path.abspath(args.output))
    model = os.path.relpath(os.path.abspath(args.model), out_dir)
    plane = os.path.relpath(os.path.join(SHARED, "plane.obj"), out_dir)
    base = json.loads(args.base) if args.base else DRAGON_BASE

    if args.flatten:
        dragons = [{"file": model, "material": "dragon", "transform": base + t} for t in field]
    else:
        dragons = [{"file": model, "material": "dragon", "transform": base, "instances": field}]
    # From outside one corner, a little above the dragons' heads, looking
    # along the diagonal: near dragons large, the far ones down to pixels.
    edge = round(half + args.spacing, 3)
    scene = {
        "render": {"width": args.width, "height": args.height, "spp": args.spp, "seed": 0,
                   "integrator": args.integrator, "max_depth": 4},
        "camera": {"origin": [-edge, 3.0, edge], "look_at": [round(-edge + 7.0, 3), 0.7, round(edge - 7.0, 3)], "up": [0, 1, 0],
                   "fov": 50},
        "materials": {
            "dragon": {"type": "phong", "kd": [0.55, 0.38, 0.12], "ks": [0.35, 0.3, 0.2], "shininess": 40},
            "floor": {"type": "diffuse", "kd": [0.35, 0.37, 0.33]},
        },
        "lights": [
            {"type": "directional", "direction": [0.55, -0.45, -0.7], "irradiance": [2.6, 2.3, 1.9]},
            {"type": "directional", "direction": [-0.4, -0.8, 0.45], "irradiance": [0.25, 0.3, 0.4]},
        ],
        "objects": dragons + [
            {"file": plane, "material": "floor", "transform": [{"scale": [edge + 50, 1, edge + 50]}]},
        ],
    }
    # A sky: seen under direct, and lighting the scene as well under path.
    scene["background"] = [0.45, 0.55, 0.7]
    os.makedirs(out_dir, exist_ok=True)
    with open(args.output, "w") as f:
        json.dump(scene, f, separators=(",", ":"))
        f.write("\n")


if __name__ == "__main__":
    main()
