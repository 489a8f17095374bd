#!/usr/bin/env python3
"""Local search over the walk's balance feedback (walk.balance.*, not in the 46-parameter genome)
on a set of simulated worlds: the re-tune of issue 20 point 5.

A (mu/mu, lambda) evolution strategy in the unit box of the 13 balance parameters: each
generation the current mean and lambda-1 Gaussian perturbations of it are scored on every
condition with `stride sim walk --json`, and the mean moves to the weighted mean of the best mu.
A condition scores 1 + (40 - time to goal) / 200 when the walk reaches its goal, less 0.5 per
0.2 rad of heading change at the goal beyond 0.1 rad (from a `--record` trace); 0.9 when it
stays up without one (backward, turning); sideways, 0.45 plus 0.45 x the progress the commanded
way (mean torso y over the last 2 s, from a `--record` trace) per 0.1 m, capped at 0.9; and
0.8 x survival / 30 s when it falls. A candidate's fitness is the mean over the conditions plus
half the worst, so one failing world weighs more than a slow one. Every run is deterministic
(the worlds' seeds) and the search's own draws come from --seed, so the same command writes the
same result.

    optimiser/tools/retune_balance.py --stride build/release/bin/stride \\
        --conditions forward-steps --start firmware/config/balance-identified.json \\
        --generations 10 --out best.json

--space stepping (or all) searches the closed-loop stepping gains of issue 29
(walk.compliance.*, walk.capture.*) too; --fixed FILE sets further parameters in every candidate.

Conditions: a preset name (below) or a JSON file with a list of objects
{"vx", "vy", "vth", "seed", "step" (physics step, us), "duration", "urdf", "law", "imu", "engine"}.
The world defaults to the identified MX servo and the CM730 IMU with noise on.
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

SPACE = {  # name: search range (inside the firmware's registered bounds)
    "walk.balance.ankle_pitch_gain": (0.0, 1.0),
    "walk.balance.ankle_roll_gain": (0.0, 1.0),
    "walk.balance.hip_pitch_gain": (0.0, 1.0),
    "walk.balance.hip_roll_gain": (0.0, 1.0),
    "walk.balance.filter_time": (0.0, 0.2),
    "walk.balance.deadband": (0.0, 0.2),
    "walk.balance.max_shift": (0.02, 0.5),
    "walk.balance.pitch_angle_gain": (0.0, 20.0),
    "walk.balance.roll_angle_gain": (0.0, 20.0),
    "walk.balance.tilt_filter_time": (0.05, 3.0),
    "walk.balance.tilt_reference_time": (0.0, 20.0),
    "walk.balance.double_support_weight": (0.0, 1.0),
    "walk.balance.start_sway_steps": (0.0, 10.0),
}
STEPPING = {  # the closed-loop stepping of issue 29 (walk.compliance.*, walk.capture.*)
    "walk.compliance.gain": (0.0, 1.2),
    "walk.compliance.back_emf_gain": (0.0, 1.2),
    "walk.capture.step_gain_x": (0.0, 1.5),
    "walk.capture.step_gain_y": (0.0, 1.5),
    "walk.capture.timing_gain": (0.0, 10.0),
    "walk.capture.learn_steps": (1.0, 12.0),
}
STEPPING_START = {"walk.compliance.gain": 0.0, "walk.compliance.back_emf_gain": 0.0,
                  "walk.capture.step_gain_x": 0.0, "walk.capture.step_gain_y": 0.0,
                  "walk.capture.timing_gain": 0.0, "walk.capture.learn_steps": 4.0}
NAMES = list(SPACE)


def fail(message):
    """Bad input: one line naming what was wrong, exit 2 (the project's command-line contract)."""
    print(f"retune_balance: {message}", file=sys.stderr)
    sys.exit(2)


def load_json(path, option):
    """A JSON file given on the command line, or one line naming the option and the problem."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        fail(f"{option}: cannot read {path}: {e}")


def preset(name):
    steps = {"forward-steps": (2000, 1000, 500), "forward-2ms": (2000,)}
    if name in steps:
        return [dict(vx=1, seed=s, step=st, duration=35) for st in steps[name] for s in (1, 2, 3)]
    if name == "stepping":  # every direction at two steps, forward on two seeds
        conds = [dict(vx=1, seed=s, step=st, duration=30) for st in (2000, 1000) for s in (1, 2)]
        conds += [dict(seed=1, step=st, duration=20, **c) for st in (2000, 1000)
                  for c in (dict(vx=-1), dict(vy=1), dict(vy=-1), dict(vth=1), dict(vth=-1))]
        return conds
    if name == "omni":
        conds = [dict(vx=1, seed=s, step=st, duration=35) for st in (2000, 1000) for s in (1, 2, 3)]
        conds += [dict(seed=1, step=st, duration=20, vth=v) for st in (2000, 1000) for v in (1, -1)]
        conds += [dict(seed=1, step=2000, duration=20, **c)
                  for c in (dict(vx=-1), dict(vy=1), dict(vy=-1))]
        return conds
    fail(f"--conditions: no preset '{name}' (forward-steps, forward-2ms, omni, stepping) and no "
         "such file")


def read_torso(record):
    """(t, x, y, yaw) of every tick of a `--record` trajectory."""
    out = []
    with open(record) as f:
        next(f)  # header
        for line in f:
            row = json.loads(line)
            w, qx, qy, qz = row["torso"]["q"]
            yaw = math.atan2(2 * (w * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
            out.append((row["t"], row["torso"]["p"][0], row["torso"]["p"][1], yaw))
    return out


def mean_over_last(samples, key, last_s):
    """Mean of samples[key] over the last `last_s` seconds of `samples` (the sway averaged out)."""
    if not samples:
        return 0.0
    tail = [s[key] for s in samples if s[0] >= samples[-1][0] - last_s]
    return sum(tail) / len(tail)


def mean_torso_y(record, last_s=2.0):
    """Mean torso y [m] over the last `last_s` of a `--record` trajectory."""
    return mean_over_last(read_torso(record), 2, last_s)


def heading_at_goal(record, goal_x=2.5):
    """Mean torso yaw [rad] over the second before the torso first passes x = goal_x (or the end)."""
    samples = read_torso(record)
    end = next((i for i, s in enumerate(samples) if s[1] >= goal_x), len(samples) - 1)
    return mean_over_last(samples[: end + 1], 3, 1.0)


def run(stride, params, cond):
    fd, path = tempfile.mkstemp(suffix=".json")
    with os.fdopen(fd, "w") as f:
        json.dump(params, f)
    args = [stride, "sim", "walk", "--params", path, "--json", "--noise", "on",
            "--duration", str(cond.get("duration", 35)), "--seed", str(cond.get("seed", 1)),
            "--servo-law", cond.get("law", "identified"), "--imu", cond.get("imu", "cm730"),
            "--physics-step-us", str(cond.get("step", 2000)),
            "--engine", cond.get("engine", "simbody")]
    for key in ("vx", "vy", "vth"):
        if key in cond:
            args += ["--" + key, str(cond[key])]
    if "urdf" in cond:
        args += ["--urdf", cond["urdf"]]
    record = None
    if cond.get("vy") or cond.get("vx", 0) > 0:  # score sideways progress, forward heading
        fd, record = tempfile.mkstemp(suffix=".jsonl")
        os.close(fd)
        args += ["--record", record]
    try:
        out = subprocess.run(args, capture_output=True, text=True, check=False)
        try:
            result = json.loads(out.stdout)
        except json.JSONDecodeError:  # a world that explodes prints its reason on stderr
            lines = out.stderr.strip().splitlines()
            return {"error": lines[-1] if lines else "no output"}
        if record and cond.get("vy"):
            result["sideways_m"] = mean_torso_y(record) * (1 if cond["vy"] > 0 else -1)
        elif record:
            result["heading_rad"] = heading_at_goal(record)
        return result
    finally:
        os.unlink(path)
        if record:
            os.unlink(record)


def score(result):
    if "error" in result:
        return 0.0
    if result.get("time_to_goal_s") is not None:
        # Straight: no loss up to 0.1 rad of heading change at the goal, 0.5 per 0.2 rad beyond.
        crooked = max(0.0, abs(result.get("heading_rad", 0.0)) - 0.1) / 0.2
        return max(0.5, 1.0 + (40.0 - result["time_to_goal_s"]) / 200.0 - 0.5 * crooked)
    if not result["fell"]:
        if "sideways_m" in result:  # half for standing, half for 0.1 m the commanded way
            return 0.45 + 0.45 * min(1.0, max(0.0, result["sideways_m"] / 0.1))
        return 0.9
    return 0.8 * min(result["fall_time_s"], 30.0) / 30.0


def label(result):
    if "error" in result:
        return "ERR"
    if result.get("time_to_goal_s") is not None:
        heading = f"/{result['heading_rad']:+.2f}" if "heading_rad" in result else ""
        return f"G{result['time_to_goal_s']:.1f}{heading}"
    if result["fell"]:
        return f"F{result['fall_time_s']:.1f}"
    return f"y{result['sideways_m']:+.2f}" if "sideways_m" in result else "ok"


def to_params(u, fixed=None):
    params = dict(fixed or {})
    params.update({n: lo + min(1.0, max(0.0, x)) * (hi - lo) for n, x, (lo, hi) in
                   zip(NAMES, u, SPACE.values())})
    return params


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--stride", default="build/release/bin/stride")
    ap.add_argument("--conditions", default="forward-steps")
    ap.add_argument("--start", required=True,
                    help="parameter file naming all 13 walk.balance.* values to start from")
    ap.add_argument("--out", required=True, help="best parameter set found (JSON)")
    ap.add_argument("--generations", type=int, default=10)
    ap.add_argument("--lambda", dest="lam", type=int, default=12)
    ap.add_argument("--mu", type=int, default=4)
    ap.add_argument("--sigma", type=float, default=0.12, help="step in the unit box")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--space", choices=("balance", "stepping", "all"), default="balance",
                    help="the 13 walk.balance.* gains, the stepping gains (walk.compliance.*, "
                         "walk.capture.*), or both")
    ap.add_argument("--fixed", help="parameter file (JSON object) set in every candidate, e.g. "
                                    "wider velocity limits; the searched names override it")
    a = ap.parse_args()
    global NAMES, SPACE
    if a.space == "stepping":
        SPACE = dict(STEPPING)
    elif a.space == "all":
        SPACE = {**SPACE, **STEPPING}
    NAMES = list(SPACE)
    fixed = load_json(a.fixed, "--fixed") if a.fixed else {}
    if not isinstance(fixed, dict):
        fail(f"--fixed: {a.fixed}: expected an object of parameter values")
    if not os.access(a.stride, os.X_OK):
        fail(f"--stride: not an executable: {a.stride}")
    if not 1 <= a.mu <= a.lam:
        fail(f"--mu must be in [1, --lambda], got {a.mu}")
    conds = (load_json(a.conditions, "--conditions") if os.path.isfile(a.conditions)
             else preset(a.conditions))
    if not isinstance(conds, list) or not all(isinstance(c, dict) for c in conds) or not conds:
        fail(f"--conditions: {a.conditions}: expected a non-empty list of objects")
    start = load_json(a.start, "--start")
    if not isinstance(start, dict):
        fail(f"--start: {a.start}: expected an object of parameter values")
    for n in NAMES:
        if n not in start and n in STEPPING_START:
            start[n] = STEPPING_START[n]  # the stepping gains start off
        if n not in start:
            fail(f"--start: {a.start} does not set {n}")
    mean = [(start[n] - lo) / (hi - lo) for n, (lo, hi) in SPACE.items()]
    rng = random.Random(a.seed)
    weights = [math.log(a.mu + 0.5) - math.log(i + 1) for i in range(a.mu)]
    best = (-1.0, None, "")
    with ThreadPoolExecutor(a.jobs) as pool:
        for gen in range(a.generations):
            pop = [mean] + [[m + a.sigma * rng.gauss(0, 1) for m in mean]
                            for _ in range(a.lam - 1)]
            pop = [[min(1.0, max(0.0, x)) for x in u] for u in pop]
            scored = []
            for u in pop:
                results = list(pool.map(lambda c, p=to_params(u, fixed): run(a.stride, p, c),
                                        conds))
                values = [score(r) for r in results]
                fitness = sum(values) / len(values) + 0.5 * min(values)
                scored.append((fitness, u, " ".join(label(r) for r in results)))
            scored.sort(key=lambda s: -s[0])
            if scored[0][0] > best[0]:
                best = scored[0]
                with open(a.out + ".tmp", "w") as f:
                    json.dump(to_params(best[1], fixed), f, indent=1, sort_keys=True)
                os.replace(a.out + ".tmp", a.out)
            mean = [sum(w * s[1][k] for w, s in zip(weights, scored)) / sum(weights)
                    for k in range(len(NAMES))]
            print(f"generation {gen + 1}/{a.generations}: best {scored[0][0]:.3f} "
                  f"(so far {best[0]:.3f}) | {scored[0][2]}", flush=True)
    print(f"best {best[0]:.3f} written to {a.out}: {best[2]}")


if __name__ == "__main__":
    main()
