#!/usr/bin/env python3
"""The optimiser in a calibrated world (issue 45 point 4): on robots of a calibration_study.py
run kept with --keep DIR, the seed's walk task (optimiser/configs/walk.json) is optimised once
in the nominal world and once in each robot's calibrated world (robotNN.fitted.json as the
task's "world"); then Ind_O and each run's picks (the report's fastest and knee) walk on the
true robot (its URDF and world file, noise on) for --seeds.

Per robot and pick it reports Obj1 (time to 2.5 m, the 40 s limit for a fall or no goal) in
the world it was optimised in and on the true robot, the gain over Ind_O in each, the share of
the gain kept on the true robot (true gain / optimised gain) and the falls on the true robot.

  python3 tests/bench/calibration_optimise.py --keep DIR --out RUNS [--robots 0,1,4,5,6]
      [--pop 40] [--generations 50] [--seeds 1,2,3,4,5] [--jobs 2] [--json OUT]
      [--stride build/release/bin/stride]

A run already in RUNS that reached its last generation is reused, so a stopped study resumes
(a run stopped half-way is started again). Runs
skip the validation (--no-validate): the true robot is the validation here.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CONFIG = os.path.join(ROOT, "optimiser", "configs", "walk.json")
LIMIT_S = 40.0


def log(text):
    print(text, file=sys.stderr, flush=True)


def finished(run, generations):
    """True if `run` holds a run that reached its last generation (a stopped one is redone)."""
    try:
        with open(os.path.join(run, "generations.jsonl")) as f:
            lines = [json.loads(x) for x in f if x.strip()]
    except (OSError, ValueError):
        return False
    return bool(lines) and lines[-1].get("generation") == generations


def optimise(args, name, world):
    out = os.path.join(args.out, name)
    if finished(out, args.generations):
        return out
    with open(CONFIG) as f:
        config = json.load(f)
    config["pop"], config["generations"] = args.pop, args.generations
    if world:
        config["world"] = os.path.abspath(world)
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, name + ".config.json")
    with open(path, "w") as f:
        json.dump(config, f, indent=1)
    log("optimise %s (pop %d, %d generations)" % (name, args.pop, args.generations))
    subprocess.run(["nice", args.stride, "optimise", "--config", path, "--out", out, "--jobs",
                    str(args.jobs), "--no-validate"], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    return out


def picks(args, run):
    """{"Ind_O": file, "fastest": file, "knee": file} and each one's Obj1 in the run's world."""
    text = subprocess.run([args.stride, "report", run], capture_output=True, text=True,
                          check=True).stdout
    out = {}
    for line in text.splitlines():
        m = re.match(r"^(Ind_O|fastest|knee)\s+f1\s+([-\d.]+)\s+f2\s+([-\d.]+)(.*?)(\S+\.json)?$",
                     line.strip())
        if m and m.group(1) not in out:
            out[m.group(1)] = {"obj1": float(m.group(2)),
                               "file": os.path.join(run, m.group(5)) if m.group(5) else None}
    start = os.path.join(run, "ind_o.json")
    with open(CONFIG) as f:
        genes = json.load(f)["genes"]
    with open(start, "w") as f:
        json.dump({g["parameter"]: g["start"] for g in genes}, f, indent=1)
    out["Ind_O"]["file"] = start
    return out


def on_true_robot(args, params, robot):
    base = os.path.join(args.keep, robot)
    times, falls = [], 0
    for seed in args.seed_list:
        cmd = ["nice", args.stride, "sim", "walk", "--vx", "1", "--duration", "%g" % LIMIT_S,
               "--params", params, "--world", base + ".world.json", "--urdf", base + ".urdf",
               "--seed", str(seed), "--json"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode not in (0, 1):
            raise SystemExit("calibration_optimise: %s: %s" % (" ".join(cmd), r.stderr.strip()))
        j = json.loads(r.stdout.strip().splitlines()[-1])
        falls += bool(j["fell"])
        reached = j.get("time_to_goal_s")
        times.append(reached if reached is not None and not j["fell"] else LIMIT_S)
    return statistics.median(times), falls


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--keep", required=True)
    ap.add_argument("--out", required=True, help="folder for the optimisation runs")
    ap.add_argument("--robots", default="0,1,4,5,6")
    ap.add_argument("--pop", type=int, default=40)
    ap.add_argument("--generations", type=int, default=50)
    ap.add_argument("--seeds", default="1,2,3,4,5")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--json")
    ap.add_argument("--stride", default=os.path.join(ROOT, "build", "release", "bin", "stride"))
    args = ap.parse_args()
    args.seed_list = [int(s) for s in args.seeds.split(",")]
    robots = ["robot%02d" % int(k) for k in args.robots.split(",")]
    for r in robots:
        if not os.path.exists(os.path.join(args.keep, r + ".fitted.json")):
            raise SystemExit("calibration_optimise: no %s.fitted.json in %s (not calibrated)"
                             % (r, args.keep))
    nominal = picks(args, optimise(args, "nominal", None))
    rows = []
    print("| robot | world optimised in | pick | Obj1 there [s] | gain there | Obj1 on the true "
          "robot [s] | gain there | gain kept | falls |")
    print("|---|---|---|---|---|---|---|---|---|")
    for robot in robots:
        calibrated = picks(args, optimise(args, robot + "-calibrated",
                                          os.path.join(args.keep, robot + ".fitted.json")))
        start_true, start_falls = on_true_robot(args, calibrated["Ind_O"]["file"], robot)
        print("| %s | - | Ind_O | %.2f (calibrated), %.2f (nominal) | - | %.2f | - | - | %d of %d |"
              % (robot, calibrated["Ind_O"]["obj1"], nominal["Ind_O"]["obj1"], start_true,
                 start_falls, len(args.seed_list)))
        for world, run in (("calibrated", calibrated), ("nominal", nominal)):
            for pick in ("fastest", "knee"):
                if pick not in run or not run[pick]["file"]:
                    continue
                there = run["Ind_O"]["obj1"] - run[pick]["obj1"]
                obj1, falls = on_true_robot(args, run[pick]["file"], robot)
                gain = start_true - obj1
                kept = gain / there if there > 0 else float("nan")
                rows.append({"robot": robot, "world": world, "pick": pick,
                             "obj1_there": run[pick]["obj1"], "gain_there": there,
                             "obj1_true": obj1, "gain_true": gain, "kept": kept,
                             "falls": falls, "ind_o_true": start_true})
                print("| %s | %s | %s | %.2f | %.2f | %.2f | %.2f | %.0f %% | %d of %d |" % (
                    robot, world, pick, run[pick]["obj1"], there, obj1, gain, 100 * kept, falls,
                    len(args.seed_list)))
    for world in ("calibrated", "nominal"):
        for pick in ("fastest", "knee"):
            sel = [r for r in rows if r["world"] == world and r["pick"] == pick]
            if sel:
                print("%s %s: median gain kept %.0f %%, falls %d of %d walks" % (
                    world, pick, 100 * statistics.median(r["kept"] for r in sel),
                    sum(r["falls"] for r in sel), len(sel) * len(args.seed_list)))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"pop": args.pop, "generations": args.generations,
                       "seeds": args.seed_list, "rows": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
