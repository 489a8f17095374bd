#!/usr/bin/env python3
"""Walk straightness per direction with each CM730 profile (issue 41 point 5): `stride sim walk`
forward, backward, left, right and turning left, 20 s each, Simbody, seeds 1-3, with
`--imu cm730` (the stock 10-bit table) and `--imu cm730-nimbro` (NimbRo's 16-bit table and the
magnetometer the heading hold then fuses). From the `--record` trace: the heading change is the
torso's yaw (unwrapped) averaged over the last 5 s minus its yaw at 1 s (the end of the start
blend; the mean, because the torso yaws to and fro by up to 0.2 rad within a step pair); the
drift is the torso's displacement across the commanded direction (in the frame of its 1 s pose)
at the end; the progress is the displacement along it. Turning: yaw rate over 5-20 s and how far the torso
wandered (its largest distance from the start). Runs two simulations at a time under `nice`.

  python3 tests/bench/walk_straightness_per_profile.py [--seeds 1,2,3] [--params FILE]
      [--stride build/release/bin/stride] [--json OUT] [-- extra sim options]

Default parameters: the firmware's defaults (the faithful world's walk). A third row runs the
NimbRo profile with the magnetometer unused (walk.balance.heading_mag_time 0: its 16-bit gyro
alone), to tell what the finer gyro does from what the magnetometer does.
"""
import argparse
import concurrent.futures
import json
import math
import os
import statistics
import sys
import tempfile

from sim_trace import walk_trace

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DIRECTIONS = [  # name, walk command, direction of progress in the start frame [rad] or None
    ("forward", ["--vx", "1"], 0.0),
    ("backward", ["--vx", "-1"], math.pi),
    ("left", ["--vy", "1"], math.pi / 2),
    ("right", ["--vy", "-1"], -math.pi / 2),
    ("turn left", ["--vth", "1"], None),
]
# label, --imu, parameter writes on top of --params
PROFILES = [
    ("cm730", "cm730", {}),
    ("cm730-nimbro", "cm730-nimbro", {}),
    ("cm730-nimbro, magnetometer unused", "cm730-nimbro", {"walk.balance.heading_mag_time": 0.0}),
]


def run_one(stride, params, imu, seed, command, direction, extra, t0=1.0, t1=20.0):
    cmd = ["nice", stride, "sim", "walk", "--engine", "simbody", "--imu", imu, "--seed",
           str(seed), "--duration", str(t1), "--json"] + command + extra
    if params:
        cmd += ["--params", params]
    result, unwrapped = walk_trace(cmd)

    def at(t):
        return min(unwrapped, key=lambda s: abs(s[0] - t))

    end = unwrapped[-1][0] - 1.0 if result["fell"] else t1
    a, b = at(t0), at(end)
    row = {"fell": bool(result["fell"]), "state_hash": result["state_hash"]}
    if direction is None:
        c = at(5.0)
        row["yaw_rate"] = (b[2] - c[2]) / (b[0] - c[0]) if b[0] - c[0] > 1.0 else float("nan")
        row["wander_m"] = max(math.hypot(s[1][0] - a[1][0], s[1][1] - a[1][1])
                              for s in unwrapped if s[0] >= t0)
        return row
    heading = a[2] + direction
    dx, dy = b[1][0] - a[1][0], b[1][1] - a[1][1]
    row["progress_m"] = dx * math.cos(heading) + dy * math.sin(heading)
    row["drift_m"] = -dx * math.sin(heading) + dy * math.cos(heading)
    tail = [s[2] for s in unwrapped if end - 5.0 <= s[0] <= end]
    row["heading_change_rad"] = statistics.mean(tail) - a[2]
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--params", default="")
    ap.add_argument("--stride", default=os.path.join(ROOT, "build/release/bin/stride"))
    ap.add_argument("--json", default="")
    ap.add_argument("extra", nargs="*")
    args = ap.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    base = {}
    if args.params:
        with open(args.params) as f:
            base = json.load(f)
    jobs = {}
    with tempfile.TemporaryDirectory() as tmp, \
            concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        for label, imu, writes in PROFILES:
            params = ""
            if base or writes:
                params = os.path.join(tmp, f"params-{len(jobs)}.json")
                with open(params, "w") as f:
                    json.dump({**base, **writes}, f)
            for name, command, direction in DIRECTIONS:
                for seed in seeds:
                    jobs[(label, name, seed)] = pool.submit(run_one, args.stride, params, imu,
                                                            seed, command, direction, args.extra)
        results = {k: f.result() for k, f in jobs.items()}
    print("| direction | profile | per seed: heading change [rad] / drift across [m] / progress "
          "[m] | mean abs heading change | mean abs drift / progress | falls |")
    print("|---|---|---|---|---|---|")
    for name, _, direction in DIRECTIONS:
        for imu, _, _ in PROFILES:
            rows = [results[(imu, name, s)] for s in seeds]
            falls = sum(r["fell"] for r in rows)
            if direction is None:
                cells = ", ".join(f"{r['yaw_rate']:.3f} rad/s, wander {r['wander_m']:.2f} m"
                                  for r in rows)
                print(f"| {name} | {imu} | {cells} | | | {falls} |")
                continue
            cells = ", ".join(f"{r['heading_change_rad']:+.3f} / {r['drift_m']:+.3f} / "
                              f"{r['progress_m']:.2f}" for r in rows)
            mean_heading = statistics.mean(abs(r["heading_change_rad"]) for r in rows)
            mean_ratio = statistics.mean(abs(r["drift_m"]) / max(abs(r["progress_m"]), 1e-6)
                                         for r in rows)
            print(f"| {name} | {imu} | {cells} | {mean_heading:.3f} | {mean_ratio:.3f} | "
                  f"{falls} |")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({f"{k[0]}|{k[1]}|{k[2]}": v for k, v in results.items()}, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
