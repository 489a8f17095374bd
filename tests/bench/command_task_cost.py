#!/usr/bin/env python3
"""The cost of the commanded-walk task (issue 53 point 2) beside the speed ramp: the wall time of
one generation of optimiser/configs/walk-command.json against one generation of walk-ramp.json
(the speed ramp of the previous main), side by side in one run on one host, and what it predicts
for the commanded walk's whole run.

  python3 tests/bench/command_task_cost.py [--stride build/release/bin/stride]
      [--ramp-stride OLD/stride] [--rounds 1] [--pop 40] [--jobs 2] [--json OUT]

A generation is the config's initial population (`generations` 1: pop evaluations, no
children), `stride optimise --no-validate --jobs 2` in a fresh directory, both configs as
shipped otherwise. The two alternate round after round (which goes first alternates too), since
speed on a shared host drifts within minutes: only the ratio of neighbouring runs counts.
--ramp-stride runs the speed ramp with another build (the previous main's); by default both run
with --stride (the speed ramp's code is the same).

The prediction: the commanded walk's whole run evaluates pop in its first generation and, as it
resamples, 2 pop (the children and the parents again) in each later one, then scores its final
front again on fresh worlds (at most pop): (1 + 2 (generations - 1) + 1) pop evaluations, each at
the wall time per evaluation measured here (at the host's load of the moment), and on two cores of
its own from the CPU time per evaluation (2 threads make 1.9x one). Later generations hold other
genomes than the first: more of them fall, and a fall ends the episode, so they cost less; an
evaluation costs at most both engines' 43.5 s without a fall. The speed ramp's first generation
is far cheaper than its later ones (its start genome cannot command most levels, so most of its
episodes end at once): the ratio compares first generations, not whole runs.
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CONFIGS = os.path.join(ROOT, "optimiser", "configs")


def one_generation(stride, name, pop, jobs, workdir):
    """(wall seconds of the generation, CPU seconds of the whole command, evaluations) of the
    config's first generation."""
    with open(os.path.join(CONFIGS, name)) as f:
        config = json.load(f)
    config.update(pop=pop, generations=1)
    out = tempfile.mkdtemp(dir=workdir)
    path = os.path.join(out, "config.json")
    with open(path, "w") as f:
        json.dump(config, f)
    start = time.monotonic()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run = subprocess.run(["nice", stride, "optimise", "--config", path, "--out",
                          os.path.join(out, "run"), "--jobs", str(jobs), "--no-validate"],
                         capture_output=True, text=True)
    elapsed = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if run.returncode != 0:
        sys.exit(f"command_task_cost: {name}: exit {run.returncode}: {run.stderr.strip()[-400:]}")
    evaluations, wall = 0, 0.0
    with open(os.path.join(out, "run", "generations.jsonl")) as f:
        for line in f:
            g = json.loads(line)
            evaluations = g["evaluations"]
            wall += g["wall_s"]
    return (wall if wall > 0 else elapsed), cpu, evaluations


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--stride", default=os.path.join(ROOT, "build", "release", "bin", "stride"))
    ap.add_argument("--ramp-stride", help="`stride` for the speed ramp (default --stride)")
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--pop", type=int, default=40, help="population of the generation (40)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--json", help="write every figure here")
    a = ap.parse_args()
    ramp_stride = a.ramp_stride or a.stride
    for b in (a.stride, ramp_stride):
        if not os.access(b, os.X_OK):
            sys.exit(f"command_task_cost: {b} is not an executable stride")
    with open(os.path.join(CONFIGS, "walk-command.json")) as f:
        command = json.load(f)
    runs = {"command": [], "ramp": []}
    with tempfile.TemporaryDirectory() as workdir:
        for k in range(a.rounds):
            order = ("command", "ramp") if k % 2 == 0 else ("ramp", "command")
            for which in order:
                stride, name = ((a.stride, "walk-command.json") if which == "command" else
                                (ramp_stride, "walk-ramp.json"))
                wall, cpu, evaluations = one_generation(stride, name, a.pop, a.jobs, workdir)
                runs[which].append({"wall_s": wall, "cpu_s": cpu, "evaluations": evaluations})
                print(f"round {k + 1}: {name}: {wall:.1f} s wall, {cpu:.1f} s CPU, "
                      f"{evaluations} evaluations", file=sys.stderr)
    ratios = [c["wall_s"] / r["wall_s"] for c, r in zip(runs["command"], runs["ramp"])]
    cpu_ratios = [c["cpu_s"] / r["cpu_s"] for c, r in zip(runs["command"], runs["ramp"])]
    per_evaluation = statistics.median(c["wall_s"] / c["evaluations"] for c in runs["command"])
    cpu_per_evaluation = statistics.median(c["cpu_s"] / c["evaluations"]
                                           for c in runs["command"])
    pop, generations = command["pop"], command["generations"]
    resample = command.get("resample", False)
    evaluations = pop * ((1 + 2 * (generations - 1) + 1) if resample else generations)
    # The host's cores were shared by the measured runs as by the predicted one (--jobs 2).
    predicted_min = evaluations * per_evaluation / 60.0
    # On two cores of its own (2 threads make 1.9x one, RESULTS.md "Evaluation cost").
    free_min = evaluations * cpu_per_evaluation / 1.9 / 60.0
    print("| config, one generation (pop %d, --jobs %d) | wall time [s], median (range) | "
          "CPU time [s], median (range) |" % (a.pop, a.jobs))
    print("|---|---|---|")
    for which, name in (("command", "walk-command.json"), ("ramp", "walk-ramp.json")):
        w = [r["wall_s"] for r in runs[which]]
        c = [r["cpu_s"] for r in runs[which]]
        print(f"| {name} | {statistics.median(w):.1f} ({min(w):.1f}-{max(w):.1f}) | "
              f"{statistics.median(c):.1f} ({min(c):.1f}-{max(c):.1f}) |")
    print()
    print(f"walk-command / walk-ramp, one generation: wall {statistics.median(ratios):.2f}x "
          f"({min(ratios):.2f}-{max(ratios):.2f}), CPU {statistics.median(cpu_ratios):.2f}x "
          f"({min(cpu_ratios):.2f}-{max(cpu_ratios):.2f})")
    print(f"walk-command per evaluation: {per_evaluation:.2f} s wall with --jobs {a.jobs} on "
          f"this host as loaded, {cpu_per_evaluation:.2f} s CPU; its whole run (pop {pop}, "
          f"{generations} generations{', resampled' if resample else ''}: {evaluations} "
          f"evaluations) predicts {predicted_min:.0f} min at this load, {free_min:.0f} min on "
          f"two free cores")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"runs": runs, "ratios": ratios, "cpu_ratios": cpu_ratios,
                       "per_evaluation_s": per_evaluation,
                       "cpu_per_evaluation_s": cpu_per_evaluation,
                       "predicted_evaluations": evaluations, "predicted_min": predicted_min,
                       "predicted_free_min": free_min}, f, indent=1)


if __name__ == "__main__":
    main()
