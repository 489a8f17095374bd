#!/usr/bin/env python3
"""The cost of an evaluation (issue 42 point 5), side by side: two `stride` builds (the previous
main's and this one) run the same short optimisations in alternation, round after round, and the
table gives each one's evaluations per second and their ratio per round (median and range).
Speed on these hosts drifts within minutes, so only the ratio of neighbouring runs counts.

  python3 tests/bench/evaluation_cost.py --old OLD/stride [--new build/release/bin/stride]
      [--rounds 3] [--tasks walk,ramp,ramp2,getup] [--configs DIR] [--json OUT]

OLD is a release build of the previous main, for example:
  git worktree add /tmp/prev <commit> && cmake -S /tmp/prev --preset release \
    && cmake --build /tmp/prev/build/release --target stride

Also measured with the new build in the same run:
  - 2 threads against 1 (`--jobs 2` against `--jobs 1`, the walk task);
  - MuJoCo's real-time factor against Simbody's (`stride sim walk --vx 1 --duration 20`),
    and the physical floor: wall time per physics step on each engine (the whole lockstep
    period's work, servo and IMU models included, divided by the physics steps).

The tasks are the shipped configs cut short (populations and generations below), so that a
round takes a few minutes; the ratio of whole runs is what the full configs would see as long
as the episodes are alike. Both builds run the same configs: this tree's optimiser/configs, or
--configs DIR (the old tree's, when the old build cannot read today's; the new build reads every
older config). Each run is `stride optimise --no-validate --jobs 2` in a fresh
directory; evaluations/s = evaluations / (sum of the generations' wall_s).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CONFIGS = os.path.join(ROOT, "optimiser", "configs")


def walk_task(c):
    c.update(pop=12, generations=3)


def ramp_task(c):
    c.update(pop=8, generations=2)


def ramp_two_engines(c):
    ramp_task(c)
    c["engines"] = ["simbody", "mujoco"]


def getup_task(c):
    c.update(pop=8, generations=2)


TASKS = {  # name: (shipped config, how it is cut short, description)
    "walk": ("walk.json", walk_task, "the seed's walk task (pop 12, 3 generations)"),
    "ramp": ("walk-ramp.json", ramp_task, "speed ramp (pop 8, 2 generations)"),
    "ramp2": ("walk-ramp.json", ramp_two_engines,
              "speed ramp, trials on both engines (pop 8, 2 generations)"),
    "getup": ("getup.json", getup_task, "get-up (pop 8, 2 generations)"),
}


def run_optimise(stride, config, jobs, workdir):
    """Evaluations per second of one run (NaN if it failed)."""
    out = tempfile.mkdtemp(dir=workdir)
    path = os.path.join(out, "config.json")
    with open(path, "w") as f:
        json.dump(config, f)
    run = subprocess.run(["nice", stride, "optimise", "--config", path, "--out",
                          os.path.join(out, "run"), "--jobs", str(jobs), "--no-validate"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        print(f"  {stride}: exit {run.returncode}: {run.stderr.strip()[-300:]}",
              file=sys.stderr)
        return float("nan")
    evaluations, wall = 0, 0.0
    with open(os.path.join(out, "run", "generations.jsonl")) as f:
        for line in f:
            g = json.loads(line)
            evaluations = g["evaluations"]
            wall += g["wall_s"]
    return evaluations / wall if wall > 0 else float("nan")


def sim_walk(stride, engine):
    """(rtf, physics steps per second of wall time) of a 20 s walk on `engine`."""
    run = subprocess.run(["nice", stride, "sim", "walk", "--vx", "1", "--duration", "20",
                          "--engine", engine, "--json"], capture_output=True, text=True)
    if run.returncode != 0:
        return float("nan"), float("nan")
    r = json.loads(run.stdout)
    steps = r["sim_time_s"] / (r.get("physics_step_us", 2000) * 1e-6)
    return r["rtf"], steps / r["wall_time_s"]


def spread(values):
    v = [x for x in values if x == x]
    if not v:
        return "-"
    return f"{statistics.median(v):.2f}x ({min(v):.2f}-{max(v):.2f})"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--old", required=True, help="`stride` of the previous main")
    ap.add_argument("--new", default=os.path.join(ROOT, "build", "release", "bin", "stride"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--tasks", default="walk,ramp,ramp2,getup")
    ap.add_argument("--configs", default=CONFIGS,
                    help="the shipped configs both builds run (default: this tree's)")
    ap.add_argument("--json", help="write every figure here")
    a = ap.parse_args()
    for b in (a.old, a.new):
        if not os.access(b, os.X_OK):
            sys.exit(f"evaluation_cost: {b} is not an executable stride")
    tasks = a.tasks.split(",")
    for t in tasks:
        if t not in TASKS:
            sys.exit(f"evaluation_cost: unknown task '{t}' (one of {', '.join(TASKS)})")
    figures = {t: {"old": [], "new": [], "ratio": []} for t in tasks}
    threads = {"one": [], "two": [], "ratio": []}
    engines = {"simbody_rtf": [], "mujoco_rtf": [], "ratio": [], "simbody_us_per_step": [],
               "mujoco_us_per_step": []}
    with tempfile.TemporaryDirectory() as workdir:
        for k in range(a.rounds):
            print(f"round {k + 1} of {a.rounds}", file=sys.stderr)
            for t in tasks:
                name, shorten, _ = TASKS[t]
                with open(os.path.join(a.configs, name)) as f:
                    config = json.load(f)
                shorten(config)
                # Alternate which build goes first, so that a drifting host favours neither.
                order = ("old", "new") if k % 2 == 0 else ("new", "old")
                rate = {}
                for which in order:
                    rate[which] = run_optimise(getattr(a, which), config, 2, workdir)
                figures[t]["old"].append(rate["old"])
                figures[t]["new"].append(rate["new"])
                figures[t]["ratio"].append(rate["new"] / rate["old"])
                print(f"  {t}: old {rate['old']:.2f}/s, new {rate['new']:.2f}/s", file=sys.stderr)
            with open(os.path.join(a.configs, "walk.json")) as f:
                config = json.load(f)
            walk_task(config)
            one = run_optimise(a.new, config, 1, workdir)
            two = run_optimise(a.new, config, 2, workdir)
            threads["one"].append(one)
            threads["two"].append(two)
            threads["ratio"].append(two / one)
            simbody = sim_walk(a.new, "simbody")
            mujoco = sim_walk(a.new, "mujoco")
            engines["simbody_rtf"].append(simbody[0])
            engines["mujoco_rtf"].append(mujoco[0])
            engines["ratio"].append(mujoco[0] / simbody[0])
            engines["simbody_us_per_step"].append(1e6 / simbody[1])
            engines["mujoco_us_per_step"].append(1e6 / mujoco[1])
    print("| task | evaluations/s, old | evaluations/s, new | new / old, median (range) |")
    print("|---|---|---|---|")
    for t in tasks:
        f = figures[t]
        print(f"| {TASKS[t][2]} | {statistics.median(f['old']):.2f} | "
              f"{statistics.median(f['new']):.2f} | {spread(f['ratio'])} |")
    print()
    print(f"2 threads against 1 (new build, walk task): {spread(threads['ratio'])}")
    print(f"MuJoCo rtf / Simbody rtf (new build, 20 s walk): {spread(engines['ratio'])}; "
          f"rtf {statistics.median(engines['simbody_rtf']):.0f}x and "
          f"{statistics.median(engines['mujoco_rtf']):.0f}x")
    print(f"wall time per physics step: Simbody "
          f"{statistics.median(engines['simbody_us_per_step']):.1f} us, MuJoCo "
          f"{statistics.median(engines['mujoco_us_per_step']):.1f} us")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"tasks": figures, "threads": threads, "engines": engines}, f, indent=1)


if __name__ == "__main__":
    main()
