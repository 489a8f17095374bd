#!/usr/bin/env python3
"""Fall and get up, per side, ground and engine (issue 43 point 5): how often and how fast the
default firmware stands up.

Two kinds of episode, each per engine (simbody, mujoco), ground (turf, soft, hard; optionally the
seed's 2 cm grass) and seed:
- lying still: `stride sim getup --lying front|back` (stood_up_s: from lying still to standing);
- knocked over: `stride sim stand --push 1,DIR,IMPULSE --after-fall getup` for DIR forward,
  backward, left and right (stood_up_s: from the fall to standing; the get-up script it chose).
With --variants DIR (the URDFs of sim_hal/models/make_variants.py) the lying-still episodes also
run on each robot variant, on turf. With --walk-params FILE the robot also walks at full forward command with that
file and is pushed at 3 s (`stride sim walk --vx 1 --push 3,DIR,IMPULSE --after-fall getup`):
a walk that stands up walks on, and the row counts those that then walk 2 m more
(walked_after_get_up_m, issue 54 point 4). With --off-model the lying-still episodes also run, on turf, in
each world file of tests/bench/worlds (servos off the model: supply 12.5 / 13.5 V, friction x1.5,
torque x0.85) and with the seed's servo law (issue 54's table). With --draws each episode also
draws its world as the get-up run's trials do (friction +-20 %, link masses +-5 %, servo strength +-10 %; optimiser/configs/
getup.json), the draw fixed by its seed.

Standing (sim::StoodUpWatch, docs/simulation.md): the motion manager back in Stand after a get-up
script, the trunk within 25 deg of vertical and its origin above 0.45 m, held for 1 s.

  python3 tests/bench/getup_per_side.py [--seeds 20] [--engines simbody,mujoco]
      [--grounds turf,soft,hard] [--pushes forward,backward,left,right] [--impulse 12]
      [--variants DIR] [--off-model] [--draws] [--first-seed 1] [--params FILE] [--duration 20] [--jobs 2]
      [--json OUT]
      [--stride build/release/bin/stride]

Prints one markdown table: per row the episodes that stood up, those that stood up at the first
attempt, the median time to stand (a robot that stayed down counts as slower than any that stood),
the slowest time of those that stood, and the medians of the peak torso acceleration and of the
peak servo load (the largest |motor torque| of any servo, the get-up task's Obj2). Two simulations at a
time under `nice` (--jobs).
"""
import argparse
import concurrent.futures
import json
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def run(job):
    """One episode; returns the job with its result (stood_up_s or None, attempts, max |a|)."""
    cmd = ["nice", job["stride"], "sim"] + job["args"] + ["--seed", str(job["seed"]), "--json"]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode not in (0, 1):
        raise RuntimeError(" ".join(cmd) + ": " + out.stderr.strip())
    result = json.loads(out.stdout.strip().splitlines()[-1])
    return dict(job, stood_up_s=result.get("stood_up_s"), attempts=result.get("get_up_attempts"),
                script=result.get("get_up_script"), max_accel=result.get("max_accel"),
                peak_load=result.get("peak_servo_torque_nm"),
                walked=result.get("walked_after_get_up_m"))


def jobs_of(a):
    seeds = range(a.first_seed, a.first_seed + a.seeds)
    common = ["--duration", str(a.duration)] + (["--params", a.params] if a.params else [])
    if a.draws:
        common += ["--friction-range", "0.2", "--mass-range", "0.05", "--strength-range", "0.1"]
    for engine in a.engines:
        for ground in a.grounds:
            world = ["--engine", engine, "--contact", ground]
            for side in ("front", "back"):
                for seed in seeds:
                    yield dict(row=(engine, ground, "lying on the " + side), seed=seed,
                               args=["getup", "--lying", side] + world + common)
            for direction in a.pushes:
                for seed in seeds:
                    push = "1,%s,%g" % (direction, a.impulse)
                    yield dict(row=(engine, ground, "pushed " + direction), seed=seed,
                               args=["stand", "--push", push, "--after-fall", "getup"] + world +
                               common)
        if a.walk_params:
            for direction in a.pushes:
                for seed in seeds:
                    push = "3,%s,%g" % (direction, a.impulse)
                    yield dict(row=(engine, "turf", "walking, pushed " + direction), seed=seed,
                               args=["walk", "--vx", "1", "--push", push, "--after-fall", "getup",
                                     "--engine", engine, "--params", a.walk_params,
                                     "--duration", str(max(a.duration, 30.0))])
        if a.off_model:
            worlds = [(w[:-5], ["--world", os.path.join(HERE, "worlds", w)])
                      for w in sorted(os.listdir(os.path.join(HERE, "worlds")))
                      if w.endswith(".json")] + [("seed servo law", ["--servo-law", "seed"])]
            for name, world in worlds:
                for side in ("front", "back"):
                    for seed in seeds:
                        yield dict(row=(engine, name, "lying on the " + side), seed=seed,
                                   args=["getup", "--lying", side, "--engine", engine] + world +
                                   common)
        if a.variants:
            for urdf in sorted(os.listdir(a.variants)):
                if not urdf.endswith(".urdf"):
                    continue
                for side in ("front", "back"):
                    for seed in seeds:
                        yield dict(row=(engine, urdf[:-5], "lying on the " + side), seed=seed,
                                   args=["getup", "--lying", side, "--engine", engine, "--urdf",
                                         os.path.join(a.variants, urdf)] + common)


def table(results):
    rows = {}
    for r in results:
        rows.setdefault(r["row"], []).append(r)
    lines = ["| engine | ground or robot | episode | stood up | first attempt | median [s] | "
             "slowest [s] | median peak \\|a\\| [m/s^2] | median peak servo load [N m] | "
             "walked 2 m more |", "|---|---|---|---|---|---|---|---|---|---|"]
    for key, rs in rows.items():
        times = [r["stood_up_s"] for r in rs if r["stood_up_s"] is not None]
        first = sum(1 for r in rs if r["stood_up_s"] is not None and r["attempts"] == 1)
        median = statistics.median(
            [r["stood_up_s"] if r["stood_up_s"] is not None else float("inf") for r in rs])
        accel = statistics.median(r["max_accel"] for r in rs)
        load = statistics.median(r["peak_load"] for r in rs)
        walking = key[2].startswith("walking")
        walked = sum(1 for r in rs if (r.get("walked") or 0.0) >= 2.0)
        lines.append("| %s | %s | %s | %d of %d | %d | %s | %s | %.0f | %.1f | %s |" % (
            key[0], key[1], key[2], len(times), len(rs), first,
            "%.2f" % median if median != float("inf") else "down",
            "%.2f" % max(times) if times else "-", accel, load,
            "%d of %d" % (walked, len(rs)) if walking else "-"))
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--seeds", type=int, default=20, help="seeds 1..N per row (default 20)")
    p.add_argument("--engines", default="simbody,mujoco")
    p.add_argument("--grounds", default="turf,soft,hard",
                   help="--contact values (turf, soft, hard, seed)")
    p.add_argument("--pushes", default="forward,backward,left,right",
                   help="push directions for the knocked-over episodes ('' for none)")
    p.add_argument("--impulse", type=float, default=12.0,
                   help="push impulse [N s] (12 topples the stand every way, FALLING.md)")
    p.add_argument("--variants", help="folder of robot variant URDFs (make_variants.py)")
    p.add_argument("--walk-params",
                   help="also walk at full forward command with this parameter file, pushed at 3 s "
                        "in each --pushes direction, and count the walks that stand and walk 2 m")
    p.add_argument("--off-model", action="store_true",
                   help="also the worlds of tests/bench/worlds and the seed's servo law, on turf")
    p.add_argument("--draws", action="store_true",
                   help="draw each episode's world as the get-up run's trials do")
    p.add_argument("--first-seed", type=int, default=1, help="the first seed (default 1)")
    p.add_argument("--params", help="parameter file for the firmware")
    p.add_argument("--duration", type=float, default=20.0, help="episode length [s] (the rules' 20)")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--json", help="write every episode's result here")
    p.add_argument("--stride", default=os.path.join(ROOT, "build/release/bin/stride"))
    a = p.parse_args()
    a.engines = [e for e in a.engines.split(",") if e]
    a.grounds = [g for g in a.grounds.split(",") if g]
    a.pushes = [d for d in a.pushes.split(",") if d]
    if a.seeds < 1:
        p.error("--seeds: at least 1, not %d" % a.seeds)
    if not os.access(a.stride, os.X_OK):
        p.error("--stride: no executable at %s (build it: cmake --build --preset release)" % a.stride)
    jobs = [dict(j, stride=a.stride) for j in jobs_of(a)]
    results = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        for i, r in enumerate(pool.map(run, jobs)):
            results.append(r)
            if (i + 1) % 20 == 0 or i + 1 == len(jobs):
                print("%d of %d episodes" % (i + 1, len(jobs)), file=sys.stderr, flush=True)
    if a.json:
        with open(a.json + ".tmp", "w") as f:
            json.dump([{k: v for k, v in r.items() if k != "stride"} for r in results], f, indent=1)
        os.replace(a.json + ".tmp", a.json)
    print(table(results))


if __name__ == "__main__":
    main()
