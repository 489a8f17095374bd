#!/usr/bin/env python3
"""Largest push the walk survives (issue 29 point 4): the forward walk (`stride sim walk --vx 1`)
is pushed on the trunk in single support with `--push T,DIR,IMPULSE`, for each direction
(forward, backward, left, right) and seed, and the impulse is bisected between the largest
survived and the smallest that made the robot fall within --after seconds of the push.

Single support: a run without a push is recorded once per seed (the runs are deterministic,
so a pushed run is the same up to the push); the push time is the middle of the first single
support (one foot with no contact point, the other with some) that begins after --at seconds
and lasts at least 0.1 s. The push lasts 10 ms (a force of IMPULSE / 0.01 s at the trunk's
centre of mass, sim_hal/include/stride/sim_hal/world_options.hpp TorsoPush).

  python3 tests/bench/push_recovery.py [--seeds 1,2,3] [--directions forward,backward,left,right]
      [--at 8] [--after 4] [--max 4] [--resolution 0.05] [--params FILE]
      [--stride build/release/bin/stride] [--json OUT] [-- extra sim options]

Default: the default (faithful) world with the firmware's defaults (the closed-loop walk of
issue 29); --params FILE overlays a parameter file (the "before" figures of tests/bench/RESULTS.md
are firmware/config/seed-walk.json then balance-identified.json: merge them into one file).
Two simulations at a time, under `nice`.
Prints, per direction, the largest impulse survived in every seed and per seed, and in how
many seeds --max itself was survived (issue 53: --vx 0.5 --max 4 --seeds 1,...,10 counts the
seeds surviving 4 N s at half speed; a seed without a single support counts as not surviving).
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def sim(args, seed, extra, duration, record=None):
    cmd = ["nice", args.stride, "sim", "walk", "--vx", str(args.vx)] + \
        (["--params", args.params] if args.params else []) + \
        ["--seed", str(seed), "--duration", "%.3f" % duration, "--json"] + extra + args.extra
    if record:
        cmd += ["--record", record]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode not in (0, 1):
        raise RuntimeError(" ".join(cmd) + ": " + out.stderr.strip())
    return json.loads(out.stdout.strip().splitlines()[-1])


def single_support_time(args, seed):
    """Middle of the first single support of >= 0.1 s after args.at (None if none)."""
    with tempfile.TemporaryDirectory() as tmp:
        record = os.path.join(tmp, "trace.jsonl")
        sim(args, seed, [], args.at + 3.0, record)
        with open(record) as f:
            next(f)
            start, foot = None, None
            for line in f:
                j = json.loads(line)
                t = j["t"]
                left = j["contacts"]["left"]["points"]
                right = j["contacts"]["right"]["points"]
                now = "left" if right == 0 and left > 0 else "right" if left == 0 and right > 0 \
                    else None
                if now != foot:
                    if foot is not None and start is not None and start >= args.at and \
                            t - start >= 0.1:
                        return 0.5 * (start + t), foot
                    start, foot = t, now
    return None, None


def survives(args, seed, t, direction, impulse):
    r = sim(args, seed, ["--push", "%.3f,%s,%.4f" % (t, direction, impulse)], t + args.after)
    return not r["fell"]


def largest(args, seed, t, direction):
    lo, hi = 0.0, args.max
    if survives(args, seed, t, direction, hi):
        return hi
    while hi - lo > args.resolution:
        mid = 0.5 * (lo + hi)
        if survives(args, seed, t, direction, mid):
            lo = mid
        else:
            hi = mid
    return lo


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--vx", type=float, default=1.0,
                    help="forward command of the walk being pushed (issue 53: 0.5, half speed)")
    ap.add_argument("--directions", default="forward,backward,left,right")
    ap.add_argument("--at", type=float, default=8.0, help="push in the first single support "
                    "after this time [s]")
    ap.add_argument("--after", type=float, default=4.0, help="survive this long after it [s]")
    ap.add_argument("--max", type=float, default=4.0, help="largest impulse tried [N s]")
    ap.add_argument("--resolution", type=float, default=0.05, help="[N s]")
    ap.add_argument("--params", help="parameter file over the firmware's defaults")
    ap.add_argument("--stride", default=os.path.join(ROOT, "build", "release", "bin", "stride"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--json", help="write the results here")
    ap.add_argument("extra", nargs="*", help="more `stride sim walk` options (after --)")
    args = ap.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    directions = args.directions.split(",")
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        times = dict(zip(seeds, pool.map(lambda s: single_support_time(args, s), seeds)))
        jobs = {}
        for seed in seeds:
            t, foot = times[seed]
            if t is None:
                print("seed %d: no single support after %.1f s (fell?)" % (seed, args.at))
                continue
            for d in directions:
                jobs[(d, seed)] = pool.submit(largest, args, seed, t, d)
        results = {k: v.result() for k, v in jobs.items()}
    print("push in single support (time, stance foot) per seed: " + ", ".join(
        "%d: %.2f s %s" % (s, times[s][0], times[s][1]) for s in seeds if times[s][0]))
    print("| direction | largest survived in every seed [N s] | seeds surviving %.2f N s | "
          "per seed |" % args.max)
    print("|---|---|---|---|")
    for d in directions:
        per = [results[(d, s)] for s in seeds if (d, s) in results]
        print("| %s | %.2f | %d of %d | %s |" % (
            d, min(per) if per else float("nan"), sum(p >= args.max for p in per), len(seeds),
            ", ".join("%.2f" % p for p in per)))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"times": {str(s): times[s] for s in seeds},
                       "largest": {"%s/%d" % k: v for k, v in results.items()}}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
