#!/usr/bin/env python3
"""How closely the identified MX servos follow the spline walk at each step frequency (issue 53
point 1): `stride sim walk` with walk.engine 1 and walk.spline.frequency f, forward at full
command and in place, seeds 1-3; for each leg joint group the RMS and the 95th percentile of
|goal - measured position| from 4 s to the end (after the start blend and the steps in place),
in degrees, the median over the seeds; a run that fell is marked. The goal is what the
firmware sent (compliance offsets included), the position what the servo reached.

  python3 tests/bench/spline_walk_tracking.py [--frequencies 1.0,1.5,...] [--seeds 1,2,3]
      [--engine simbody] [--stride build/release/bin/stride] [--params FILE] [-- extra]
"""
import argparse
import concurrent.futures
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
GROUPS = {  # trajectory joint names (right, left)
    "hip roll": ("right_hip_roll", "left_hip_roll"),
    "hip pitch": ("right_hip_pitch", "left_hip_pitch"),
    "knee": ("right_knee_pitch", "left_knee_pitch"),
    "ankle pitch": ("right_ankle_pitch", "left_ankle_pitch"),
    "ankle roll": ("right_ankle_roll", "left_ankle_roll"),
}


def run_one(stride, base, frequency, command, seed, engine, extra, t0=4.0, duration=10.0):
    params = dict(base)
    params.update({"walk.engine": 1, "walk.spline.frequency": frequency})
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "params.json")
        with open(path, "w") as f:
            json.dump(params, f)
        record = os.path.join(tmp, "trace.jsonl")
        cmd = ["nice", stride, "sim", "walk", "--params", path, "--engine", engine, "--seed",
               str(seed), "--duration", str(duration), "--json", "--record", record]
        out = subprocess.run(cmd + command + extra, capture_output=True, text=True)
        if out.returncode not in (0, 1):
            raise RuntimeError(" ".join(cmd) + ": " + out.stderr.strip())
        result = json.loads(out.stdout.strip().splitlines()[-1])
        errors = {g: [] for g in GROUPS}
        with open(record) as f:
            names = json.loads(next(f))["joints"]
            index = {n: i for i, n in enumerate(names)}
            for line in f:
                j = json.loads(line)
                if j["t"] < t0:
                    continue
                for g, pair in GROUPS.items():
                    for n in pair:
                        i = index[n]
                        errors[g].append(abs(j["goals"][i] - j["joints"][i]))
    figures = {}
    for g, e in errors.items():
        if not e:
            figures[g] = (float("nan"), float("nan"))
            continue
        e.sort()
        rms = math.sqrt(sum(x * x for x in e) / len(e))
        figures[g] = (math.degrees(rms), math.degrees(e[int(0.95 * (len(e) - 1))]))
    return result["fell"], figures


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frequencies", default="1.0,1.5,2.0,2.5,3.0,3.5")
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--engine", default="simbody")
    ap.add_argument("--params", help="base parameter file (walk.engine is set to 1)")
    ap.add_argument("--stride", default=os.path.join(ROOT, "build", "release", "bin", "stride"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("extra", nargs="*", help="more `stride sim walk` options (after --)")
    args = ap.parse_args()
    base = json.load(open(args.params)) if args.params else {}
    frequencies = [float(f) for f in args.frequencies.split(",")]
    seeds = [int(s) for s in args.seeds.split(",")]
    commands = {"forward": ["--vx", "1"], "in place": []}
    jobs = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for f in frequencies:
            for name, command in commands.items():
                for s in seeds:
                    jobs[(f, name, s)] = pool.submit(run_one, args.stride, base, f, command, s,
                                                     args.engine, args.extra)
    print("| frequency (Hz) | steps/s | walk | falls | " +
          " | ".join("%s RMS / p95 (deg)" % g for g in GROUPS) + " |")
    print("|---|---|---|---|" + "---|" * len(GROUPS))
    for f in frequencies:
        for name in commands:
            runs = [jobs[(f, name, s)].result() for s in seeds]
            falls = sum(1 for fell, _ in runs if fell)
            cells = []
            for g in GROUPS:
                rms = statistics.median(fig[g][0] for _, fig in runs)
                p95 = statistics.median(fig[g][1] for _, fig in runs)
                cells.append("%.2f / %.2f" % (rms, p95))
            print("| %.1f | %.1f | %s | %d/%d | %s |" % (f, 2 * f, name, falls, len(runs),
                                                       " | ".join(cells)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
