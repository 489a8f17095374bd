#!/usr/bin/env python3
"""Judge a calibration by what it predicts (issue 45 point 3): for each robot of a
calibration_study.py run kept with --keep DIR, the true robot (its URDF and world file, noise
on), its calibrated world (the nominal URDF with robotNN.fitted.json) and the nominal world
(faithful) each walk with the firmware's defaults, and the script compares the figures:

  time to 2.5 m   `stride sim walk --vx 1`, 30 s: time_to_goal_s (a fall or no goal: none)
  peak accel      the same run's max_accel (the seed walk's Obj2) [m/s^2]
  speeds          forward, backward, left, right [m/s] and turning both ways [rad/s], 20 s,
                  displacement from 5 s to 20 s (walk_speed_per_direction.py's measure)
  push            the largest impulse the forward walk survives in single support, for each of
                  forward, backward, left and right (push_recovery.py's bisection) [N s]
  get-up          `stride sim getup --lying front|back`, 20 s (issue 56 point 4): whether the
                  default get-up stands within 10 s in most seeds (judged by agreement with the
                  true robot), and its median time to stand [s]

Each figure is the median over --seeds. A figure is predicted when the calibrated world's
error against the true robot is within 5 % of the true value and within half the nominal
world's error (the issue's target: whichever is tighter). The table gives, per figure, how
many robots meet it, and the median errors of both worlds.

  python3 tests/bench/calibration_prediction.py --keep DIR [--seeds 1,2,3] [--jobs 2]
      [--json OUT] [--stride build/release/bin/stride] [--push-resolution 0.1]

--json keeps every world's figures; with an existing file, worlds already measured are
reused (a stopped run resumes). Two simulations at a time under `nice`; progress on stderr.
"""
import argparse
import concurrent.futures
import glob
import json
import math
import os
import statistics
import subprocess
import sys
from types import SimpleNamespace

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import push_recovery  # noqa: E402  (single_support_time, largest)
import walk_speed_per_direction as speeds  # noqa: E402  (DIRECTIONS, run_one)

PUSHES = ("forward", "backward", "left", "right")


def log(text):
    print(text, file=sys.stderr, flush=True)


def walk_forward(stride, seed, world):
    cmd = ["nice", stride, "sim", "walk", "--vx", "1", "--duration", "30", "--seed", str(seed),
           "--json"] + world
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode not in (0, 1):
        raise RuntimeError(" ".join(cmd) + ": " + out.stderr.strip())
    r = json.loads(out.stdout.strip().splitlines()[-1])
    return {"time_to_goal_s": None if r["fell"] else r.get("time_to_goal_s"),
            "peak_accel": r["max_accel"]}


def get_up(stride, seed, world, side):
    cmd = ["nice", stride, "sim", "getup", "--lying", side, "--duration", "20", "--seed",
           str(seed), "--json"] + world
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode not in (0, 1):
        raise RuntimeError(" ".join(cmd) + ": " + out.stderr.strip())
    return json.loads(out.stdout.strip().splitlines()[-1]).get("stood_up_s")


def median(values):
    values = [v for v in values if v is not None and not math.isnan(v)]
    return statistics.median(values) if values else None


def figures(args, world, pool):
    """The figures of one world (`world`: its stride sim options), medians over the seeds."""
    seeds = args.seed_list
    walks = [pool.submit(walk_forward, args.stride, s, world) for s in seeds]
    runs = {(name, s): pool.submit(speeds.run_one, args.stride, "defaults", "simbody", s, cmd,
                                   coord, world)
            for name, cmd, coord, _ in speeds.DIRECTIONS for s in seeds}
    push_args = SimpleNamespace(stride=args.stride, params=None, extra=world, at=8.0, after=4.0,
                                max=4.0, resolution=args.push_resolution)
    times = dict(zip(seeds, pool.map(lambda s: push_recovery.single_support_time(push_args, s),
                                     seeds)))
    pushes = {(d, s): pool.submit(push_recovery.largest, push_args, s, times[s][0], d)
              for d in PUSHES for s in seeds if times[s][0] is not None}
    getups = {(side, s): pool.submit(get_up, args.stride, s, world, side)
              for side in ("front", "back") for s in seeds}
    out = {"time_to_2.5m_s": median([w.result()["time_to_goal_s"] for w in walks]),
           "peak_accel_mps2": median([w.result()["peak_accel"] for w in walks])}
    for name, _, _, sign in speeds.DIRECTIONS:
        values = [runs[(name, s)].result() for s in seeds]
        out["speed " + name] = median([sign * v["speed"] for v in values if not v["fell"]])
    for d in PUSHES:
        out["push " + d + " N s"] = median([pushes[(d, s)].result() for s in seeds
                                            if (d, s) in pushes])
    for side in ("front", "back"):
        times = [getups[(side, s)].result() for s in seeds]
        stood = [t for t in times if t is not None and t <= 10.0]
        out["get-up " + side + " stands"] = 1.0 if 2 * len(stood) > len(times) else 0.0
        out["get-up " + side + " s"] = median(times)
    return out


def judge(true, calibrated, nominal, agreement=False):
    """(predicted, calibrated error, nominal error) of one figure; None if a value is missing.
    For a yes/no figure (`agreement`), predicted means the same answer as the true robot."""
    if agreement and None not in (true, calibrated, nominal):
        return calibrated == true, float(calibrated != true), float(nominal != true)
    if true is None or calibrated is None or nominal is None or true == 0:
        return None
    e_cal, e_nom = abs(calibrated - true) / abs(true), abs(nominal - true) / abs(true)
    return e_cal <= min(0.05, 0.5 * e_nom) + 1e-12, e_cal, e_nom


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--keep", required=True, help="calibration_study.py --keep folder")
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--push-resolution", type=float, default=0.1, help="[N s]")
    ap.add_argument("--json", help="write (and resume from) the figures here")
    ap.add_argument("--stride", default=os.path.join(ROOT, "build", "release", "bin", "stride"))
    args = ap.parse_args()
    args.seed_list = [int(s) for s in args.seeds.split(",")]
    if not os.access(args.stride, os.X_OK):
        raise SystemExit("calibration_prediction: no stride binary at %s" % args.stride)
    robots = sorted(os.path.basename(p)[:-len(".fitted.json")]
                    for p in glob.glob(os.path.join(args.keep, "robot*.fitted.json")))
    if not robots:
        raise SystemExit("calibration_prediction: no robotNN.fitted.json in %s" % args.keep)
    done = {}
    if args.json and os.path.exists(args.json):
        with open(args.json) as f:
            done = json.load(f).get("worlds", {})
    worlds = {"nominal": []}
    for r in robots:
        base = os.path.join(args.keep, r)
        worlds[r + " true"] = ["--world", base + ".world.json", "--urdf", base + ".urdf"]
        worlds[r + " calibrated"] = ["--world", base + ".fitted.json"]
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for k, (name, world) in enumerate(worlds.items()):
            if name in done:
                continue
            log("world %d of %d: %s" % (k + 1, len(worlds), name))
            try:
                done[name] = figures(args, world, pool)
            except RuntimeError as e:
                raise SystemExit("calibration_prediction: %s: %s" % (name, e))
            if args.json:
                with open(args.json + ".tmp", "w") as f:
                    json.dump({"seeds": args.seed_list, "worlds": done}, f, indent=1)
                os.replace(args.json + ".tmp", args.json)
    names = list(done["nominal"])
    print("| figure | calibrated predicts (within 5 % and half the nominal error) | "
          "median error calibrated | median error nominal |")
    print("|---|---|---|---|")
    rows = {}
    for figure in names:
        judged = [judge(done[r + " true"].get(figure), done[r + " calibrated"].get(figure),
                        done["nominal"][figure], figure.endswith(" stands")) for r in robots]
        judged = [j for j in judged if j is not None]
        rows[figure] = judged
        if not judged:
            print("| %s | - | - | - |" % figure)
            continue
        print("| %s | %d of %d | %.1f %% | %.1f %% |" % (
            figure, sum(j[0] for j in judged), len(judged),
            100 * statistics.median(j[1] for j in judged),
            100 * statistics.median(j[2] for j in judged)))
    missing = [r for r in robots for f in names
               if judge(done[r + " true"].get(f), done[r + " calibrated"].get(f),
                        done["nominal"][f], f.endswith(" stands")) is None]
    if missing:
        print("\nnot judged (a world fell or never reached the goal in every seed): %d "
              "robot-figure pairs" % len(missing))
    return 0


if __name__ == "__main__":
    sys.exit(main())
