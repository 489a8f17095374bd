#!/usr/bin/env python3
"""Walk speed per direction on each engine and ground (issues 29 and 41): `stride sim walk`
forward, backward, left, right and turning both ways, 20 s each, seeds 1-3; the speed of one
run is the torso's displacement from 5 s to 20 s (x, y, or yaw unwrapped) divided by 15 s,
and the table shows the median over the seeds, with the falls. Runs two simulations at a
time under `nice`.

  python3 tests/bench/walk_speed_per_direction.py [--engines simbody,mujoco] [--seeds 1,2,3]
      [--params FILE]... [--grounds turf,soft,hard] [--stride build/release/bin/stride]
      [--worlds faithful,FILE.json] [--curves] [--only forward,backward,...] [--json OUT]
      [-- extra sim options]

--params may be given several times (one table row per file, engine and ground); "defaults"
is the firmware without a parameter file. --grounds are `--contact` values: turf (the
default world's), soft (deep turf), hard (carpet), seed (the thesis's 2 cm grass).
--worlds adds one row per world (`faithful`, the default, or a world file such as the
off-model servos' in tests/bench/worlds/). --curves adds two columns: a curve (command 1, 0,
0.5; speed along the walk's path, the torso's distance travelled over the window) and a
diagonal (0.7, 0.7, 0; speed along the path likewise).
Default parameters: tests/bench/params/balance-identified-wide.json (balance-identified.json
with the issue's wider velocity limits) on the faithful world (--servo-law identified --imu
cm730).
"""
import argparse
import concurrent.futures
import json
import math
import os
import statistics
import sys

from sim_trace import walk_trace

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DIRECTIONS = [  # name, walk command, which coordinate, sign of progress
    ("forward", ["--vx", "1"], "x", 1),
    ("backward", ["--vx", "-1"], "x", -1),
    ("left", ["--vy", "1"], "y", 1),
    ("right", ["--vy", "-1"], "y", -1),
    ("turn left", ["--vth", "1"], "yaw", 1),
    ("turn right", ["--vth", "-1"], "yaw", -1),
]
CURVES = [  # --curves: the path's length over the window, so sign 1
    ("curve", ["--vx", "1", "--vth", "0.5"], "path", 1),
    ("diagonal", ["--vx", "0.7", "--vy", "0.7"], "path", 1),
]


def run_one(stride, params, engine, seed, command, coordinate, extra, t0=5.0, t1=20.0):
    cmd = ["nice", stride, "sim", "walk"] + ([] if params == "defaults" else ["--params", params])
    cmd += ["--servo-law", "identified", "--imu", "cm730", "--engine", engine, "--seed",
            str(seed), "--duration", str(t1), "--json"] + command + extra
    result, unwrapped = walk_trace(cmd)

    def at(t):
        return min(unwrapped, key=lambda s: abs(s[0] - t))

    # A run that fell is measured up to 1 s before the fall (not the fall itself).
    end = unwrapped[-1][0] - 1.0 if result["fell"] else t1
    a, b = at(t0), at(min(t1, end))
    span = b[0] - a[0]
    if coordinate == "path":
        window = [s for s in unwrapped if a[0] <= s[0] <= b[0]]
        travelled = sum(math.hypot(q[1][0] - p[1][0], q[1][1] - p[1][1])
                        for p, q in zip(window, window[1:]))
        speed = travelled / span if span > 1.0 else float("nan")
    else:
        value = {"x": lambda s: s[1][0], "y": lambda s: s[1][1], "yaw": lambda s: s[2]}[coordinate]
        speed = (value(b) - value(a)) / span if span > 1.0 else float("nan")
    return {"fell": bool(result["fell"]), "fall_time_s": result.get("fall_time_s"),
            "speed": speed, "state_hash": result["state_hash"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--engines", default="simbody,mujoco")
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--params", action="append",
                    help="parameter file (repeatable; 'defaults': none)")
    ap.add_argument("--grounds", default="",
                    help="comma-separated --contact values (default: the world's own)")
    ap.add_argument("--worlds", default="faithful",
                    help="comma-separated worlds: faithful or world files (one row each)")
    ap.add_argument("--curves", action="store_true", help="add the curve and the diagonal")
    ap.add_argument("--only", help="comma-separated directions to run (default: all)")
    ap.add_argument("--stride", default=os.path.join(ROOT, "build", "release", "bin", "stride"))
    ap.add_argument("--json", help="write every run's result here")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("extra", nargs="*", help="more `stride sim walk` options (after --)")
    args = ap.parse_args()
    engines = args.engines.split(",")
    seeds = [int(s) for s in args.seeds.split(",")]
    files = args.params or [os.path.join(HERE, "params", "balance-identified-wide.json")]
    grounds = args.grounds.split(",") if args.grounds else [""]
    worlds = args.worlds.split(",")
    directions = DIRECTIONS + (CURVES if args.curves else [])
    if args.only:
        directions = [d for d in directions if d[0] in args.only.split(",")]
    jobs = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for params in files:
            for world in worlds:
                for ground in grounds:
                    extra = (["--contact", ground] if ground else []) + args.extra
                    if world != "faithful":
                        extra = ["--world", world] + extra
                    for engine in engines:
                        for name, command, coordinate, _ in directions:
                            for seed in seeds:
                                jobs[(params, world, ground, engine, name, seed)] = pool.submit(
                                    run_one, args.stride, params, engine, seed, command,
                                    coordinate, extra)
    results = {k: v.result() for k, v in jobs.items()}
    print("| parameters | world | ground | engine | " + " | ".join(d[0] for d in directions) +
          " |")
    print("|---|---|---|---|" + "---|" * len(directions))
    for params in files:
        for world in worlds:
            for ground in grounds:
                for engine in engines:
                    cells = []
                    for name, _, _, sign in directions:
                        runs = [results[(params, world, ground, engine, name, s)] for s in seeds]
                        speeds = [r["speed"] for r in runs if not math.isnan(r["speed"])]
                        falls = sum(r["fell"] for r in runs)
                        cell = "%.3f" % statistics.median(speeds) if speeds else "-"
                        if falls:
                            cell += ", falls %d/%d" % (falls, len(runs))
                        cells.append(cell)
                    print("| %s | %s | %s | %s | %s |" % (
                        os.path.basename(params), os.path.basename(world), ground or "world's",
                        engine, " | ".join(cells)))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"%s/%s/%s/%s/%s/%d" % k: v for k, v in results.items()}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
