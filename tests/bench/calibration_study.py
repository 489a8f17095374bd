#!/usr/bin/env python3
"""A study on many unknown robots (issue 45 point 2): draws N perturbed robots at random from the
distribution below, records the identification routine on each (`stride identify`, noise on),
calibrates each from the nominal start world (`stride calibrate --fit LIST`) and reports, per
value, the share of robots where the fit lands within 20 % of the perturbation
(|fitted - true| <= 0.2 |true - nominal|) or within the value's absolute tolerance when the
perturbation is small, and the median absolute error. The issue's target: at least 80 % for
every value --fit offers without a warning.

  python3 tests/bench/calibration_study.py --robots N [--seed S] [--fit LIST] [--jobs J]
      [--calibrate-jobs 2] [--max-evals 250] [--subsets 0] [--window 15] [--json OUT]
      [--resume] [--keep DIR]
      [--stride build/release/bin/stride]

The distribution (robot k of seed S: random.Random(S * 1000003 + k), draws in a fixed order):
  through the URDF (sim_hal/models/igus_op.urdf, written as make_variants.py writes variants):
    trunk mass and inertia x U(0.9, 1.1); trunk centre of mass x, y each + U(-15, 15) mm;
    every other link's mass and inertia x U(0.97, 1.03) and its centre of mass x, y
    + U(-2, 2) mm, independently (not a --fit value: the model error a calibration lives with);
  through the world file (docs/formats.md "World files"):
    MX-64 and MX-106 torque x U(0.85, 1.15) each; servo friction x U(0.8, 1.3);
    latency U{0, 1, 2, 3} ticks; supply U(13.5, 16.2) V (nominal 14.8);
    gyro bias per axis U(-0.05, 0.05) rad/s, accelerometer bias per axis U(-0.3, 0.3) m/s^2,
    to which noise on adds the episode's own draw (N(0, 0.01) rad/s, N(0, 0.1) m/s^2,
    sim_hal/src/igus_defaults.cpp): the true bias is the sum, read from `stride identify --json`.
The firmware keeps its nominal robot description (as on a real robot). Unless trunk_mass is in
--fit, the calibration is given the robot's weighed mass (--robot-mass: the URDF's total), which
sets the trunk mass scale; that row is reported as "set", not fitted. Unless voltage is in
--fit, stride calibrate reads the supply from the logs (the CM730's reading); that row is
reported as "measured".

Absolute tolerances (TOLERANCE below): scales 0.02, supply 0.1 V, latency 0 ticks (exact),
trunk CoM 2 mm, gyro bias 0.005 rad/s, accelerometer bias 0.05 m/s^2.
Robots run one after another (--jobs 1) with the calibration's replays on --calibrate-jobs
threads; at most two processes at once, under `nice`. Progress on stderr; exit 1 on a failure.
"""
import argparse
import json
import math
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "sim_hal", "models"))
import make_variants  # noqa: E402  (scale_link, shift_com: the variants' URDF edits)

DEFAULT_FIT = ("torque_mx64,torque_mx106,friction,latency,trunk_com_x,trunk_com_y,"
               "gyro_bias,accel_bias")
NOMINAL_VOLTAGE = 14.8
AXES = ("x", "y", "z")
# value: (nominal, absolute tolerance, unit, scale printed)
TOLERANCE = {
    "torque_mx64": (1.0, 0.02, "x", 1), "torque_mx106": (1.0, 0.02, "x", 1),
    "friction": (1.0, 0.02, "x", 1), "voltage": (NOMINAL_VOLTAGE, 0.1, "V", 1),
    "latency": (0, 0, "ticks", 1), "trunk_mass": (1.0, 0.02, "x", 1),
    "trunk_com_x": (0.0, 0.002, "mm", 1000), "trunk_com_y": (0.0, 0.002, "mm", 1000),
    **{"gyro_bias_" + a: (0.0, 0.005, "rad/s", 1) for a in AXES},
    **{"accel_bias_" + a: (0.0, 0.05, "m/s^2", 1) for a in AXES},
}


def log(text):
    print(text, file=sys.stderr, flush=True)


def expand_fit(text):
    names = []
    for name in text.split(","):
        if name in ("gyro_bias", "accel_bias"):
            names += [name + "_" + a for a in AXES]
        elif name == "all":
            names += list(TOLERANCE)
        elif name in TOLERANCE:
            names.append(name)
        else:
            raise SystemExit("calibration_study: --fit: unknown value '%s'" % name)
    return [n for n in TOLERANCE if n in names]


def draw_robot(seed, k):
    """The true values of robot k and its URDF edits (a fixed order of draws)."""
    rng = random.Random(seed * 1000003 + k)
    truth = {
        "trunk_mass": rng.uniform(0.9, 1.1),
        "trunk_com_x": rng.uniform(-0.015, 0.015),
        "trunk_com_y": rng.uniform(-0.015, 0.015),
        "torque_mx64": rng.uniform(0.85, 1.15),
        "torque_mx106": rng.uniform(0.85, 1.15),
        "friction": rng.uniform(0.8, 1.3),
        "latency": rng.randrange(4),
        "voltage": rng.uniform(13.5, 16.2),
    }
    for a in AXES:
        truth["gyro_bias_" + a] = rng.uniform(-0.05, 0.05)
    for a in AXES:
        truth["accel_bias_" + a] = rng.uniform(-0.3, 0.3)
    tree = ET.parse(os.path.join(ROOT, "sim_hal", "models", "igus_op.urdf"))
    links = [link for link in tree.getroot().iter("link") if link.find("inertial") is not None]
    for link in links:  # document order: the same draws on every run
        if link.get("name") == "trunk_link":
            make_variants.scale_link(link, truth["trunk_mass"])
            make_variants.shift_com(link, truth["trunk_com_x"], truth["trunk_com_y"])
        else:
            make_variants.scale_link(link, rng.uniform(0.97, 1.03))
            make_variants.shift_com(link, rng.uniform(-0.002, 0.002), rng.uniform(-0.002, 0.002))
    mass = sum(float(link.find("inertial").find("mass").get("value")) for link in links)
    tree.getroot().set("name", "igus_op_study_%d_%d" % (seed, k))
    return truth, tree, mass


def world_file(truth):
    return {"format": "stride-world", "base": "faithful", "supply_voltage_v": truth["voltage"],
            "robot": {"torque_scale": {"MX-64": truth["torque_mx64"],
                                       "MX-106": truth["torque_mx106"]},
                      "friction_scale": truth["friction"], "latency_ticks": truth["latency"]},
            "imu": {"gyro_bias_rad_s": [truth["gyro_bias_" + a] for a in AXES],
                    "accel_bias_mps2": [truth["accel_bias_" + a] for a in AXES]}}


def truth_world_file(truth):
    """The true values in the nominal model's terms (the limbs' changes stay unmodelled)."""
    w = world_file(truth)
    w["robot"]["trunk_mass_scale"] = truth["trunk_mass"]
    w["robot"]["trunk_com_offset_m"] = [truth["trunk_com_x"], truth["trunk_com_y"]]
    w["imu"] = {"gyro_bias_rad_s": [truth["gyro_bias_" + a] for a in AXES],
                "accel_bias_mps2": [truth["accel_bias_" + a] for a in AXES]}
    return w


def fitted_values(world):
    robot, imu = world.get("robot", {}), world.get("imu", {})
    scale = robot.get("torque_scale", {})
    com = robot.get("trunk_com_offset_m", [0.0, 0.0])
    out = {"torque_mx64": scale.get("MX-64", 1.0), "torque_mx106": scale.get("MX-106", 1.0),
           "friction": robot.get("friction_scale", 1.0),
           "voltage": world.get("supply_voltage_v", NOMINAL_VOLTAGE),
           "latency": robot.get("latency_ticks", 0),
           "trunk_mass": robot.get("trunk_mass_scale", 1.0),
           "trunk_com_x": com[0], "trunk_com_y": com[1]}
    for i, a in enumerate(AXES):
        out["gyro_bias_" + a] = imu.get("gyro_bias_rad_s", [0.0] * 3)[i]
        out["accel_bias_" + a] = imu.get("accel_bias_mps2", [0.0] * 3)[i]
    return out


def run(cmd, what):
    out = subprocess.run(["nice"] + cmd, capture_output=True, text=True)
    if out.returncode != 0:
        lines = [x for x in out.stderr.strip().splitlines() if x.strip()]
        raise RuntimeError("%s failed (exit %d): %s" % (what, out.returncode,
                                                        lines[-1] if lines else "no message"))
    return out


def study_robot(args, k, fit, folder):
    """Records and calibrates robot k; returns its record (truth, fit, errors)."""
    truth, tree, mass = draw_robot(args.seed, k)
    base = os.path.join(folder, "robot%02d" % k)
    tree.write(base + ".urdf", encoding="unicode", xml_declaration=True)
    with open(base + ".world.json", "w") as f:
        json.dump(world_file(truth), f, indent=1)
    started = time.time()
    cmd = [args.stride, "identify", "--out", base + ".flog", "--world", base + ".world.json",
           "--urdf", base + ".urdf", "--noise", "on", "--seed", str(args.seed * 1000 + k), "--json"]
    out = subprocess.run(["nice"] + cmd, capture_output=True, text=True)
    try:
        summary = json.loads(out.stdout.strip().splitlines()[-1])
    except (IndexError, ValueError):
        lines = [x for x in out.stderr.strip().splitlines() if x.strip()]
        raise RuntimeError("robot %d: stride identify failed (exit %d): %s" % (
            k, out.returncode, lines[-1] if lines else "no message"))
    if summary["fell"] or summary["failure"]:  # a robot the routine throws: no fit, reported
        part = [name for name, t in summary["part_start_s"].items()
                if t <= summary["ticks"] * 0.01]
        return {"robot": k, "truth": truth, "identify_s": time.time() - started,
                "calibrate_s": 0.0, "warnings": [], "fell": "%s in %s at %.1f s" % (
                    "fell" if summary["fell"] else summary["failure"],
                    max(part, key=lambda n: summary["part_start_s"][n]) if part else "?",
                    summary["ticks"] * 0.01)}
    for i, a in enumerate(AXES):  # the episode's bias: the world's plus noise's draw
        truth["gyro_bias_" + a] = summary["imu_bias"]["gyro_rad_s"][i]
        truth["accel_bias_" + a] = summary["imu_bias"]["accel_mps2"][i]
    identify_s = time.time() - started
    cmd = [args.stride, "calibrate", base + ".flog", "--fit", ",".join(args.fit_names),
           "--out", base + ".fitted.json", "--jobs", str(args.calibrate_jobs),
           "--max-evals", str(args.max_evals), "--subsets", str(args.subsets),
           "--window", "%g" % args.window, "--no-check"]
    if "trunk_mass" not in fit:
        cmd += ["--robot-mass", "%.6f" % mass]
    out = subprocess.run(["nice"] + cmd, capture_output=True, text=True)
    record = {"robot": k, "truth": truth, "robot_mass_kg": mass, "identify_s": identify_s,
              "calibrate_s": time.time() - started - identify_s}
    stderr = [x.split("\r")[-1] for x in out.stderr.splitlines() if x.strip()]
    record["warnings"] = [x for x in stderr if "warning" in x.lower() or "--fit:" in x]
    if out.returncode == 2 and any("--fit:" in x for x in stderr):
        record["refused"] = record["warnings"][-1]
        return record
    if out.returncode != 0:
        raise RuntimeError("robot %d: stride calibrate failed (exit %d): %s" % (
            k, out.returncode, stderr[-1] if stderr else "no message"))
    with open(base + ".fitted.json") as f:
        fitted = json.load(f)
    record["fitted"] = fitted_values(fitted)
    record["objective"] = {"nominal": fitted["calibration"]["objective_nominal"],
                           "fitted": fitted["calibration"]["objective"]}
    if args.truth_objective:  # J at the true values: the start of a fit of 3 replays
        with open(base + ".truth.json", "w") as f:
            json.dump(truth_world_file(truth), f, indent=1)
        run([args.stride, "calibrate", base + ".flog", "--world", base + ".truth.json", "--fit",
             "voltage", "--max-evals", "3", "--subsets", "0", "--window", "%g" % args.window,
             "--jobs", str(args.calibrate_jobs), "--out", base + ".truth-fit.json", "--no-check"],
            "robot %d: stride calibrate at the true values" % k)
        with open(base + ".truth-fit.json") as f:
            record["objective"]["truth"] = json.load(f)["calibration"]["objective_start"]
    return record


def warned_values(stride, fit):
    """The values fitted with a warning: those `stride calibrate --help` marks "(warned)", and
    those marked "(warned with OTHER)" when OTHER is fitted too."""
    text = subprocess.run([stride, "calibrate", "--help"], capture_output=True, text=True).stdout
    warned = set()
    for line in text.splitlines():
        line = line.rstrip()
        if line.endswith("(warned)"):
            warned.add(line.split()[0])
        elif line.endswith(")") and "(warned with " in line:
            if line[line.rindex("(warned with ") + len("(warned with "):-1] in fit:
                warned.add(line.split()[0])
    return warned


def report(records, names, warned):
    """One row per value: robots within tolerance, median |error|, median |perturbation|, and
    whether --fit warns about it."""
    rows = []
    for name in names:
        nominal, tol, unit, shown = TOLERANCE[name]
        errors, perturbations, within = [], [], 0
        for r in records:
            if "fitted" not in r:
                continue
            true, fit = r["truth"][name], r["fitted"][name]
            error, perturbation = abs(fit - true), abs(true - nominal)
            errors.append(error)
            perturbations.append(perturbation)
            within += error <= max(0.2 * perturbation, tol) + 1e-12
        n = len(errors)
        rows.append({"value": name, "robots": n, "within": within, "warned": name in warned,
                     "share": within / n if n else math.nan, "tolerance": tol * shown,
                     "unit": unit, "median_abs_error": statistics.median(errors) * shown
                     if n else math.nan,
                     "median_abs_perturbation": statistics.median(perturbations) * shown
                     if n else math.nan})
    return rows


def print_table(rows, records):
    print("| value | --fit warns | within 20 % or tolerance | share | tolerance | "
          "median abs error | median abs perturbation |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(("| %s | %s | %d of %d | %s | %.3g %s | %.3g %s | %.3g %s |" % (
            r["value"], "yes" if r.get("warned") else "no", r["within"], r["robots"],
            "%.0f %%" % (100 * r["share"]) if r["robots"] else "-", r["tolerance"], r["unit"],
            r["median_abs_error"], r["unit"], r["median_abs_perturbation"], r["unit"])).replace(
            "nan", "-"))
    print()
    for r in records:
        line = "robot %d: identify %.0f s, calibrate %.0f s" % (r["robot"] + 1, r["identify_s"],
                                                                r["calibrate_s"])
        if "objective" in r:
            j = r["objective"]
            line += "; J nominal %.0f, fitted %.0f" % (j["nominal"], j["fitted"])
            if "truth" in j:
                line += ", at the true values %.0f" % j["truth"]
        if "fell" in r:
            line += "; not calibrated: the robot " + r["fell"]
        elif "refused" in r:
            line += "; REFUSED: " + r["refused"]
        elif r["warnings"]:
            line += "; warned about %d values" % len(r["warnings"])
        else:
            line += "; --fit accepted without a warning"
        print(line)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--robots", type=int, default=20)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--fit", default=DEFAULT_FIT,
                   help="values to fit, as stride calibrate --fit (default %(default)s)")
    p.add_argument("--jobs", type=int, default=1, help="robots at once (each one process)")
    p.add_argument("--calibrate-jobs", type=int, default=2, help="stride calibrate --jobs")
    p.add_argument("--max-evals", type=int, default=250, help="stride calibrate --max-evals")
    p.add_argument("--subsets", type=int, default=0, help="stride calibrate --subsets")
    p.add_argument("--window", type=float, default=15, help="stride calibrate --window [s]")
    p.add_argument("--no-truth-objective", dest="truth_objective", action="store_false",
                   help="skip the replay objective J at the true values (3 more replays)")
    p.add_argument("--json", help="write the records and the table as JSON")
    p.add_argument("--resume", action="store_true",
                   help="keep the robots already in --json (same seed and --fit), run the rest")
    p.add_argument("--keep", help="folder to keep the URDFs, worlds, logs and fits in")
    p.add_argument("--stride", default=os.path.join(ROOT, "build", "release", "bin", "stride"))
    args = p.parse_args()
    if args.robots < 1 or args.jobs < 1 or args.jobs > 2:
        raise SystemExit("calibration_study: --robots must be >= 1 and --jobs 1 or 2")
    if not os.access(args.stride, os.X_OK):
        raise SystemExit("calibration_study: no stride binary at %s (build the target stride)"
                         % args.stride)
    names = expand_fit(args.fit)
    warned = warned_values(args.stride, names)
    args.fit_names = names
    report_names = names + [n for n in ("trunk_mass", "voltage") if n not in names]
    tmp = None if args.keep else tempfile.TemporaryDirectory(prefix="calibration_study_")
    folder = args.keep or tmp.name
    os.makedirs(folder, exist_ok=True)
    started, records = time.time(), []
    settings = {"max_evals": args.max_evals, "window_s": args.window, "subsets": args.subsets}
    if args.resume:
        if not args.json or not os.path.exists(args.json):
            raise SystemExit("calibration_study: --resume needs an existing --json file")
        with open(args.json) as f:
            done = json.load(f)
        if done.get("seed") != args.seed or done.get("fit") != names or \
                done.get("settings") != settings:
            raise SystemExit("calibration_study: --resume: %s has another seed, --fit or "
                             "calibration settings" % args.json)
        records = [r for r in done["records"] if r["robot"] < args.robots]
    todo = [k for k in range(args.robots) if k not in {r["robot"] for r in records}]

    def one(k):
        log("robot %d of %d: start (%.0f s elapsed)" % (k + 1, args.robots, time.time() - started))
        r = study_robot(args, k, names, folder)
        state = "fell" if "fell" in r else "refused" if "refused" in r else "fitted"
        log("robot %d of %d: %s (identify %.0f s, calibrate %.0f s, %.0f s elapsed)" % (
            k + 1, args.robots, state, r["identify_s"], r["calibrate_s"], time.time() - started))
        return r

    try:
        with ThreadPoolExecutor(args.jobs) as pool:
            for r in pool.map(one, todo):
                records.append(r)
                if args.json:  # written after every robot: a stopped study keeps its robots
                    with open(args.json, "w") as f:
                        records.sort(key=lambda r: r["robot"])
                        json.dump({"seed": args.seed, "fit": names, "settings": settings,
                                   "rows": report(records, report_names, warned),
                                   "records": records}, f, indent=1)
    except RuntimeError as e:
        raise SystemExit("calibration_study: " + str(e))
    finally:
        if tmp:
            tmp.cleanup()
    records.sort(key=lambda r: r["robot"])
    rows = report(records, report_names, warned)
    print_table(rows, records)
    if "trunk_mass" not in names:
        print("trunk_mass: set from --robot-mass (the URDF's total mass), not fitted")
    if "voltage" not in names:
        print("voltage: measured (stride calibrate reads the supply from the logs), not fitted")
    log("done: %d robots in %.0f s" % (len(records), time.time() - started))


if __name__ == "__main__":
    main()
