#!/usr/bin/env python3
"""Writes the identification scripts identify_*.json (issue 30 point 4; see IDENTIFICATION.md).

The scripts are data; this generator only keeps their many frames consistent. Run it from this
folder after changing a figure below, and commit the JSON it writes.

Poses are offsets from a symmetric igus stand (kick_right frame 1, igus.md 3.1) in URDF joint
angles: thigh and shank are both 0.200 m, so bending the knee by k with hip pitch and ankle
pitch each -k/2 keeps the hip above the ankle and the trunk upright (squat); hip rolls -d and
ankle rolls +d on both legs move the trunk sideways over the left foot with the feet flat
(a parallelogram; +d right), leaving the trunk upright.
"""
import json
import os

SERVOS = [
    "r_shoulder_pitch", "l_shoulder_pitch", "r_shoulder_roll", "l_shoulder_roll",
    "r_elbow", "l_elbow", "r_hip_yaw", "l_hip_yaw", "r_hip_roll", "l_hip_roll",
    "r_hip_pitch", "l_hip_pitch", "r_knee", "l_knee", "r_ankle_pitch", "l_ankle_pitch",
    "r_ankle_roll", "l_ankle_roll",
]
BASE = {
    "r_shoulder_pitch": 0.3927, "l_shoulder_pitch": 0.3927,
    "r_shoulder_roll": -0.1239, "l_shoulder_roll": 0.1239,
    "r_elbow": -2.4435, "l_elbow": -2.4435,
    "r_hip_yaw": -0.0292, "l_hip_yaw": 0.0292,
    "r_hip_roll": -0.0626, "l_hip_roll": 0.0626,
    "r_hip_pitch": -0.2071, "l_hip_pitch": -0.2071,
    "r_knee": 0.2560, "l_knee": 0.2560,
    "r_ankle_pitch": -0.2392, "l_ankle_pitch": -0.2392,
    "r_ankle_roll": 0.0691, "l_ankle_roll": -0.0691,
}
ARM_GAIN = 30
LEG_GAIN = 40


def pose(squat=0.0, shift_left=0.0, lean=0.0, lift_right=0.0, lift_left=0.0):
    """squat: extra knee bend [rad]; shift_left: parallelogram roll d [rad] (+ = over the left
    foot); lean: extra ankle pitch on both ankles [rad] (+ = the whole body tilts backward);
    lift_*: extra knee bend of one leg with hip and ankle pitch -k/2 (the foot rises flat)."""
    p = dict(BASE)
    for side, lift in (("r", lift_right), ("l", lift_left)):
        k = squat + lift
        p[side + "_knee"] += k
        p[side + "_hip_pitch"] -= k / 2
        p[side + "_ankle_pitch"] -= k / 2 - lean
        p[side + "_hip_roll"] -= shift_left
        p[side + "_ankle_roll"] += shift_left
    return p


def arms(forward_right=0.0, forward_left=0.0, out=0.0, elbow=None):
    """The stand with the arms moved (identify_arms): forward_*: shoulder pitch towards the front
    [rad] (negative: back); out: both shoulder rolls away from the body [rad]; elbow: both elbows'
    absolute angle [rad] (None: the stand's)."""
    p = dict(BASE)
    p["r_shoulder_pitch"] -= forward_right
    p["l_shoulder_pitch"] -= forward_left
    p["r_shoulder_roll"] -= out
    p["l_shoulder_roll"] += out
    if elbow is not None:
        p["r_elbow"] = p["l_elbow"] = elbow
    return p


def frame(duration_ms, p, leg_gain=LEG_GAIN):
    return {
        "duration_ms": duration_ms,
        "targets": [
            {"servo": s, "position": round(p[s], 4),
             "gain": ARM_GAIN if "shoulder" in s or "elbow" in s else leg_gain, "torque": 100}
            for s in SERVOS
        ],
    }


def write(name, description, frames):
    text = "{\n"
    text += '  "name": %s,\n' % json.dumps(name)
    text += '  "description": %s,\n' % json.dumps(description)
    text += '  "frames": [\n'
    for i, f in enumerate(frames):
        text += '    {"duration_ms": %d, "targets": [\n' % f["duration_ms"]
        rows = []
        for t in f["targets"]:
            rows.append('      {"servo": %-20s "position": %8.4f, "gain": %d, "torque": %d}' %
                        (json.dumps(t["servo"]) + ",", t["position"], t["gain"], t["torque"]))
        text += ",\n".join(rows) + "\n"
        text += "    ]}" + ("," if i + 1 < len(frames) else "") + "\n"
    text += "  ]\n}\n"
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), name + ".json")
    with open(path, "w") as out:
        out.write(text)
    total = sum(f["duration_ms"] for f in frames)
    print("%s: %d frames, %d ms" % (name, len(frames), total))


# Figures (justified in IDENTIFICATION.md).
LEAN = 0.06        # fore-aft sway: ankle pitch +-0.06 rad, CoM about +-2.3 cm
SWAY_MS = 1500
SQUAT = 0.70       # knee 0.256 -> 0.956 rad, hip and ankle pitch -0.35 each: trunk about 4.5 cm lower
SQUAT_SLOW_MS = 2000
SQUAT_FAST_MS = 1200
SHIFT = 0.20       # weight shift: hip roll -+0.20, ankle roll +-0.20 rad, trunk about 8 cm sideways
SHIFT_MS = 1500
STEP_SHIFT = 0.22  # steps in place: shift before lifting (see IDENTIFICATION.md)
LIFT = 0.60        # swing leg knee +0.6 rad, hip and ankle pitch -0.3: foot about 1 cm up (measured)
LIFT_MS = 1500
STEP_LEG_GAIN = 40  # (60 tilted the trunk more in the simulator)

stand = pose()
frames = [frame(1000, stand)]
for _ in range(2):  # fore-aft sway on the ankles
    frames += [frame(SWAY_MS, pose(lean=LEAN)), frame(2 * SWAY_MS, pose(lean=-LEAN)),
               frame(SWAY_MS, stand)]
for duration in (SQUAT_SLOW_MS, SQUAT_SLOW_MS, SQUAT_FAST_MS, SQUAT_FAST_MS):  # squats
    frames += [frame(duration, pose(squat=SQUAT)), frame(800, pose(squat=SQUAT)),
               frame(duration, stand), frame(800, stand)]
frames += [frame(1000, stand)]
write("identify_stand",
      "Identification routine part 1 (issue 30, IDENTIFICATION.md): fore-aft sway on the ankles "
      "(ankle pitch +-%.2f rad, 2 cycles of %d ms), then 4 squats (knee +%.2f rad, hip and ankle "
      "pitch -%.2f rad; 2 at %d ms down/up, 2 at %d ms; 800 ms holds). Legs gain %d, arms %d. "
      "Written by make_identify_scripts.py." %
      (LEAN, 4 * SWAY_MS, SQUAT, SQUAT / 2, SQUAT_SLOW_MS, SQUAT_FAST_MS, LEG_GAIN, ARM_GAIN),
      frames)

frames = [frame(1000, stand)]
for duration in (SHIFT_MS, SHIFT_MS, 1000):  # weight shifts: left, centre, right, centre
    frames += [frame(duration, pose(shift_left=SHIFT)), frame(1000, pose(shift_left=SHIFT)),
               frame(duration, stand), frame(duration, pose(shift_left=-SHIFT)),
               frame(1000, pose(shift_left=-SHIFT)), frame(duration, stand)]
frames += [frame(1000, stand)]
write("identify_shift",
      "Identification routine part 2 (issue 30, IDENTIFICATION.md): weight shifts from foot to "
      "foot, hip rolls -+%.2f rad and ankle rolls +-%.2f rad (feet flat, trunk upright), 3 cycles "
      "left-centre-right-centre (%d, %d, 1000 ms per move, 1000 ms holds). Legs gain %d, arms %d. "
      "Written by make_identify_scripts.py." % (SHIFT, SHIFT, SHIFT_MS, SHIFT_MS, LEG_GAIN, ARM_GAIN),
      frames)

frames = [frame(1000, stand, STEP_LEG_GAIN)]
for _ in range(2):  # slow steps in place: shift, lift, hold, lower, back; each side
    for side in (1, -1):
        shifted = pose(shift_left=side * STEP_SHIFT)
        lifted = pose(shift_left=side * STEP_SHIFT,
                      lift_right=LIFT if side > 0 else 0.0, lift_left=LIFT if side < 0 else 0.0)
        g = STEP_LEG_GAIN
        frames += [frame(SHIFT_MS, shifted, g), frame(700, shifted, g), frame(LIFT_MS, lifted, g),
                   frame(800, lifted, g), frame(LIFT_MS, shifted, g), frame(SHIFT_MS, stand, g)]
frames += [frame(1000, stand)]
write("identify_steps",
      "Identification routine part 3 (issue 30, IDENTIFICATION.md): slow steps in place, "
      "quasi-static: shift the weight over one foot (roll %.2f rad, %d ms), lift the other foot "
      "flat (knee +%.2f rad, hip and ankle pitch -%.2f rad, %d ms), hold 800 ms, put it down, "
      "shift back; right foot then left, twice. Legs gain %d, arms %d. "
      "Written by make_identify_scripts.py." %
      (STEP_SHIFT, SHIFT_MS, LIFT, LIFT / 2, LIFT_MS, LEG_GAIN, ARM_GAIN), frames)

# Known loads on the arms (issue 56): the arms' links are light and free of contacts, so their
# servos (MX-64) hold loads the URDF gives: the arm's weight at a lever that the shoulder angle
# sets. Each angle is held after a move from below and after a move from above: the holding
# error is (gravity torque +- friction) / (strength x gain), so the mean of the two tells the
# torque scale and their difference the friction. The arms move in antiphase (one forward, one
# back) so that the centre of mass stays over the feet. Then set-point steps: a step's rise is
# shaped by the torque (its slope) and the friction (where it stops), differently.
ARM_ELBOW = -1.2      # elbows bent 69 deg: the forearm adds a load on the elbow as well
ARM_ANGLES = (0.5, 1.0, 1.4)  # shoulder pitch from the stand's, forward for one arm, back for the other
ARM_OUT = (0.4, 0.8, 1.2)     # shoulder rolls away from the body
ARM_MOVE_MS = 800
ARM_HOLD_MS = 1200
ARM_STEP = 0.4        # set-point steps of the shoulder pitch [rad], in 20 ms
ARM_STEP_MS = 20

bent = arms(elbow=ARM_ELBOW)
frames = [frame(1000, stand), frame(1500, bent), frame(ARM_HOLD_MS, bent)]
for sign in (1, -1):  # right arm forward and left back, then the other way round
    angles = list(ARM_ANGLES) + list(reversed(ARM_ANGLES[:-1])) + [0.0]
    for a in angles:  # up through each angle, then down through each: both approaches
        p = arms(sign * a, -sign * a, elbow=ARM_ELBOW)
        frames += [frame(ARM_MOVE_MS, p), frame(ARM_HOLD_MS, p)]
for a in list(ARM_OUT) + list(reversed(ARM_OUT[:-1])) + [0.0]:
    p = arms(out=a, elbow=ARM_ELBOW)
    frames += [frame(ARM_MOVE_MS, p), frame(ARM_HOLD_MS, p)]
level = arms(0.9, -0.9, elbow=ARM_ELBOW)  # steps around a loaded angle, both directions
frames += [frame(ARM_MOVE_MS, level), frame(ARM_HOLD_MS, level)]
for step in (ARM_STEP, -ARM_STEP, ARM_STEP, -ARM_STEP):
    p = arms(0.9 + step, -0.9 - step, elbow=ARM_ELBOW)
    frames += [frame(ARM_STEP_MS, p), frame(ARM_HOLD_MS, p), frame(ARM_STEP_MS, level),
               frame(ARM_HOLD_MS, level)]
frames += [frame(1500, bent), frame(1500, stand), frame(1000, stand)]
write("identify_arms",
      "Identification routine, known loads on the arms (issue 56, IDENTIFICATION.md): elbows at "
      "%.1f rad; shoulder pitch holds at +-%s rad (one arm forward, the other back) approached "
      "from below and from above, shoulder roll holds at %s rad, then set-point steps of +-%.1f "
      "rad in %d ms around a loaded angle. Holds %d ms, moves %d ms. Legs gain %d, arms %d. "
      "Written by make_identify_scripts.py." %
      (ARM_ELBOW, "/".join("%.1f" % a for a in ARM_ANGLES), "/".join("%.1f" % a for a in ARM_OUT),
       ARM_STEP, ARM_STEP_MS, ARM_HOLD_MS, ARM_MOVE_MS, LEG_GAIN, ARM_GAIN), frames)
