#!/usr/bin/env python3
"""Designs a direct get-up script (issue 43 point 3): a cross-entropy search over the keyframes of a
four-frame template, scored by `stride sim getup` on both engines. It wrote the start scripts of the
get-up run (getup-start/get_up_front.json and get_up_back.json), which getup.json then optimises.

Why a separate search: the get-up run's genome moves each target by +-0.3 rad about its start, and a
start that never stands gives NSGA-II nothing to rank (every genome violates the constraint alike).
This search reaches a first standing get-up from a rough template, with a graded score for one that
stays down: 10 + 10 (1 - p), p the best over the episode of (centre of mass height / 0.40 m) times
the share of the weight on the feet (halved while any other link touches). A standing one scores
its stood_up_s, plus 2 s for each further get-up attempt (a retry, or a fall after standing).
Both scripts are symmetric (left-side URDF angles, mirrored).

Stages, each a cross-entropy search (population --pop, the best 5 set the next mean and spread):
  design: from the template, spread 15 % of each range, on Simbody and MuJoCo turf (front: the
          worst of the two plus a tenth of their mean; back: their mean);
  robust8, robust12: from an earlier stage's mean, spread 2-3 % (--spread), the mean over 8
          or 12 worlds: both engines on turf, hard and soft ground and the make_variants.py
          robots (heavier trunk, CoM moved, a leg 5 % heavier), several seeds;
  random: the mean over --worlds (16) randomised worlds, alternately Simbody and MuJoCo, a
          quarter each on turf, hard, soft and the seed's grass, each with the get-up run's
          draws (friction +-20 %, link masses +-5 %, servo strength +-10 %) on its own seed
          (--world-seed the first); for a script that stands in the fixed worlds but not yet
          in drawn ones (--from SCRIPT.json starts at a firmware script);
  mixed: robust12's worlds, the seed's grass on both engines and --worlds (20) of random's, so
          that what a script gains in the drawn worlds it must not lose in the nominal ones or
          on the robot variants.

The chain that wrote getup-start/ is in optimiser/RESULTS.md ("Direct get-ups"). A rerun follows
the same method but need not find the same bits (the other side's script in the search's data
folder was then a template, a get-up that fails can end on the other side, the stand pose was
then rounded to 0.01 rad, now read from firmware/scripts/stand.json, and a further attempt was
then not charged 2 s).

  python3 optimiser/configs/getup_keyframe_search.py front|back
      [--stage design|robust8|robust12|random|mixed] [--iters 15] [--pop 24] [--worlds N]
      [--seed 1] [--world-seed 11] [--from STATE.json|SCRIPT.json] [--out STATE.json]
      [--script OUT.json] [--variants DIR] [--stride build/release/bin/stride]

Run from the repository root; two simulations at a time. The state file holds the search's mean
and best; --script writes the best as a firmware script. Deterministic for a given --seed.
"""
import argparse
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
from multiprocessing import Pool

MIRROR = {'shoulder_pitch': 1, 'shoulder_roll': -1, 'elbow': 1, 'hip_yaw': -1, 'hip_roll': -1,
          'hip_pitch': 1, 'knee': 1, 'ankle_pitch': 1, 'ankle_roll': -1}
# The igus stand pose, left side, from the firmware's stand script (the frame every get-up ends in).
STAND = {t['servo'][2:]: t['position']
         for t in json.load(open('firmware/scripts/stand.json'))['frames'][0]['targets']
         if t['servo'].startswith('l_') and t['servo'][2:] in MIRROR}
LIMITS = dict(shoulder_pitch=(-2.8, 2.8), elbow=(-2.6, 0.1), hip_yaw=(-0.2, 0.8),
              hip_roll=(-0.2, 1.0), hip_pitch=(-2.2, 0.8), knee=(0.0, 2.6),
              ankle_pitch=(-1.4, 1.1), ankle_roll=(-0.7, 0.7))
FRONT_LIMITS = dict(LIMITS, shoulder_pitch=(-2.8, 1.0), hip_roll=(-0.2, 0.8))
# Templates: (duration_ms, the joints this frame moves; the others keep the previous frame's).
# Front: push the chest up on straight arms; fold the legs under the hips; arms back, squat
# over the feet; stand. Back: arms push behind while the hips flex; sit up into a frog squat
# (knees open); arms forward, lean over the feet; stand.
TEMPLATES = {
    'front': [(300, dict(shoulder_pitch=-1.4, shoulder_roll=0.2, elbow=-0.2, hip_pitch=-0.1,
                         knee=0.0, ankle_pitch=0.0)),
              (500, dict(shoulder_pitch=-1.2, hip_pitch=-2.2, knee=2.6, ankle_pitch=-1.2)),
              (500, dict(shoulder_pitch=-0.3, elbow=0.0, ankle_pitch=-1.4)),
              (700, dict(STAND))],
    'back': [(350, dict(shoulder_pitch=1.2, shoulder_roll=0.2, elbow=0.0, hip_pitch=-0.8,
                        knee=0.5, ankle_pitch=0.0)),
             (500, dict(shoulder_pitch=0.5, hip_pitch=-2.2, knee=2.6, ankle_pitch=-1.0,
                        hip_roll=0.5, hip_yaw=0.4, ankle_roll=-0.4)),
             (400, dict(shoulder_pitch=-1.5, hip_pitch=-2.0, knee=2.5, ankle_pitch=-1.2,
                        hip_roll=0.3, hip_yaw=0.2, ankle_roll=-0.3)),
             (700, dict(STAND))],
}
SEARCHED = {'front': ['shoulder_pitch', 'elbow', 'hip_pitch', 'knee', 'ankle_pitch', 'hip_roll'],
            'back': ['shoulder_pitch', 'elbow', 'hip_yaw', 'hip_roll', 'hip_pitch', 'knee',
                     'ankle_pitch', 'ankle_roll']}
DESCRIPTION = {
    'front': 'Get up from lying face down, directly (issue 43): the arms push the chest up, the '
             'legs fold under the hips, the arms swing back as the robot squats over its feet, '
             'then it rises to the igus stand pose. Symmetric, URDF joint angles',
    'back': 'Get up from lying on the back, directly (issue 43): the arms push down behind the '
            'back as the hips flex, the robot sits up into a frog squat (knees open), the arms '
            'swing forward as it leans over its feet, then it rises to the igus stand pose. '
            'Symmetric, URDF joint angles',
}


def frames_of(side):
    """The template's frames as full left-side poses."""
    pose, out = dict(STAND), []
    for duration, moves in TEMPLATES[side]:
        pose = dict(pose, **moves)
        out.append((duration, dict(pose)))
    return out


def script_json(side, frames, description):
    out = {'name': 'get_up_' + side, 'description': description, 'frames': []}
    for duration, pose in frames:
        targets = []
        for joint, sign in MIRROR.items():
            for prefix, s in (('r', sign), ('l', 1)):
                targets.append({'servo': '%s_%s' % (prefix, joint),
                                'position': pose[joint] * s, 'gain': 100,
                                'torque': 100})
        out['frames'].append({'duration_ms': int(round(duration)), 'targets': targets})
    return out


def spec_of(side):
    """[(name, lo, hi, start)]: the searched joints of every frame but the last, and all durations."""
    spec, frames = [], frames_of(side)
    for i, (duration, pose) in enumerate(frames):
        if i < len(frames) - 1:
            for joint in SEARCHED[side]:
                limits = FRONT_LIMITS if side == 'front' else LIMITS
                spec.append(('frame%d.%s' % (i + 1, joint),) + limits[joint] + (pose[joint],))
        spec.append(('frame%d.dur' % (i + 1), 100 if i < len(frames) - 1 else 200,
                     1200 if i < len(frames) - 1 else 1500, duration))
    return spec


def frames_from(side, spec, x):
    frames = [[d, dict(p)] for d, p in frames_of(side)]
    for (key, lo, hi, _), v in zip(spec, x):
        v = min(hi, max(lo, v))
        frame, joint = key.split('.')
        i = int(frame[5:]) - 1
        if joint == 'dur':
            frames[i][0] = v
        else:
            frames[i][1][joint] = v
    return frames


def x_of_script(side, spec, script):
    """The search vector of a firmware script (its left-side targets and durations)."""
    frames = script['frames']
    if len(frames) != len(TEMPLATES[side]):
        sys.exit('--from: %d frames, the %s template has %d' %
                 (len(frames), side, len(TEMPLATES[side])))
    x = []
    for key, _, _, _ in spec:
        frame, joint = key.split('.')
        f = frames[int(frame[5:]) - 1]
        if joint == 'dur':
            x.append(float(f['duration_ms']))
        else:
            x.append(next(t['position'] for t in f['targets'] if t['servo'] == 'l_' + joint))
    return x


def progress(trace):
    best = 0.0
    with open(trace) as f:
        next(f)
        for line in f:
            j = json.loads(line)
            fz = j['contacts']['left']['force'][2] + j['contacts']['right']['force'][2]
            share = min(1.0, max(0.0, fz / 65.0))  # the robot's weight, about 6.6 kg
            if j['contacts']['other'] > 0:
                share *= 0.5
            best = max(best, min(1.0, j['com'][2] / 0.40) * share)
    return best


def episode(job):
    stride, data, side, world = job
    with tempfile.TemporaryDirectory() as tmp:
        trace = os.path.join(tmp, 't.jsonl')
        cmd = [stride, 'sim', 'getup', '--lying', side, '--json', '--duration', '6',
               '--record', trace] + world
        r = subprocess.run(cmd, capture_output=True, text=True,
                           env=dict(os.environ, STRIDE_DATA_DIR=data))
        if r.returncode not in (0, 1):
            raise RuntimeError(' '.join(cmd) + ': ' + r.stderr.strip())
        d = json.loads(r.stdout)
        if d.get('stood_up_s') is not None:  # 2 s more for each further attempt: a retry, or a
            return d['stood_up_s'] + 2.0 * (d['get_up_attempts'] - 1)  # fall after standing
        return 10.0 + 10.0 * (1.0 - progress(trace))


def worlds(stage, variants, first_seed=11, count=16):
    s, m = ['--engine', 'simbody'], ['--engine', 'mujoco']
    if stage == 'design':
        return [s, m]
    v = lambda name: ['--urdf', os.path.join(variants, name + '.urdf')]
    if stage == 'mixed':
        grass = ['--contact', 'seed']
        return (worlds('robust12', variants) + [s + grass, m + grass] +
                worlds('random', variants, first_seed, count))
    if stage == 'random':
        draws = ['--friction-range', '0.2', '--mass-range', '0.05', '--strength-range', '0.1']
        grounds = ('turf', 'hard', 'soft', 'seed')
        return [(s if i % 2 == 0 else m) + ['--contact', grounds[i * 4 // count],
                                             '--seed', str(first_seed + i)] + draws
                for i in range(count)]
    if stage == 'robust8':
        return [s, s + ['--contact', 'hard'], s + ['--contact', 'soft'],
                s + v('trunk_mass_plus_10pct'), s + v('trunk_com_1cm_backward') + ['--seed', '2'],
                m, m + ['--contact', 'hard'], m + v('trunk_mass_plus_10pct') + ['--seed', '3']]
    return [s, s + ['--contact', 'hard', '--seed', '4'], s + ['--contact', 'soft', '--seed', '5'],
            s + v('trunk_mass_plus_10pct') + ['--seed', '2'],
            s + v('trunk_com_1cm_left') + ['--seed', '6'],
            m, m + ['--contact', 'hard', '--seed', '4'], m + ['--contact', 'soft', '--seed', '5'],
            m + v('trunk_mass_plus_10pct') + ['--seed', '3'],
            m + v('trunk_com_1cm_left') + ['--seed', '6'],
            m + v('trunk_com_1cm_forward') + ['--seed', '2'],
            m + v('right_leg_plus_5pct') + ['--seed', '7']]


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    p.add_argument('side', choices=('front', 'back'))
    p.add_argument('--stage', default='design',
                   choices=('design', 'robust8', 'robust12', 'random', 'mixed'))
    p.add_argument('--spread', type=float,
                   help='first spread, share of each range (design 0.15, robust 0.03)')
    p.add_argument('--iters', type=int, default=15)
    p.add_argument('--pop', type=int, default=24)
    p.add_argument('--seed', type=int, default=1)
    p.add_argument('--world-seed', type=int, default=11,
                   help='random: the first world seed (a further stage draws other worlds)')
    p.add_argument('--worlds', type=int, help='random, mixed: how many drawn worlds (16, 20)')
    p.add_argument('--from', dest='start',
                   help='state file of an earlier stage (its mean), or a firmware script')
    p.add_argument('--out', default='getup_search_state.json')
    p.add_argument('--script', help='write the best as a firmware script here')
    p.add_argument('--variants', help='make_variants.py URDFs (robust stage; written if missing)')
    p.add_argument('--stride', default='build/release/bin/stride')
    a = p.parse_args()
    spec = spec_of(a.side)
    mean = [s[3] for s in spec]
    if a.start:
        start = json.load(open(a.start))
        mean = x_of_script(a.side, spec, start) if 'frames' in start else start['mean']
    share = a.spread if a.spread is not None else 0.15 if a.stage == 'design' else 0.03
    spread = [(s[2] - s[1]) * share for s in spec]
    tmp = tempfile.mkdtemp(prefix='getup-search-')
    variants = a.variants or os.path.join(tmp, 'variants')
    if a.stage in ('robust8', 'robust12', 'mixed') and not os.path.isdir(variants):
        subprocess.run([sys.executable, 'sim_hal/models/make_variants.py', variants], check=True)
    data = os.path.join(tmp, 'data')
    shutil.copytree('firmware/scripts', os.path.join(data, 'scripts'))
    os.symlink(os.path.abspath('firmware/config'), os.path.join(data, 'config'))
    ws = worlds(a.stage, variants, a.world_seed,
                a.worlds or (20 if a.stage == 'mixed' else 16))
    mean_of = a.stage != 'design' or a.side == 'back'
    rng = random.Random(a.seed)
    best = (math.inf, mean)
    with Pool(2) as pool:
        for it in range(a.iters):
            xs = [mean] + [[min(s[2], max(s[1], rng.gauss(m, d)))
                            for s, m, d in zip(spec, mean, spread)] for _ in range(a.pop - 1)]
            scores = []
            for x in xs:  # one candidate at a time: the script file is the candidate
                with open(os.path.join(data, 'scripts', 'get_up_%s.json' % a.side), 'w') as f:
                    json.dump(script_json(a.side, frames_from(a.side, spec, x), 'search'), f)
                r = pool.map(episode, [(os.path.abspath(a.stride), data, a.side, w) for w in ws])
                scores.append(sum(r) / len(r) if mean_of else max(r) + 0.1 * sum(r) / len(r))
            order = sorted(range(a.pop), key=lambda i: scores[i])
            if scores[order[0]] < best[0]:
                best = (scores[order[0]], xs[order[0]])
            elite = [xs[i] for i in order[:5]]
            mean = [sum(e[k] for e in elite) / 5 for k in range(len(spec))]
            spread = [max(0.004 * (s[2] - s[1]),
                          math.sqrt(sum((e[k] - mean[k]) ** 2 for e in elite) / 5))
                      for k, s in enumerate(spec)]
            print('iteration %d: best %.3f, median %.3f, best so far %.3f' %
                  (it, scores[order[0]], sorted(scores)[a.pop // 2], best[0]), flush=True)
            with open(a.out, 'w') as f:
                json.dump({'side': a.side, 'stage': a.stage, 'mean': mean, 'best': best[1],
                           'best_score': best[0], 'spec': spec}, f, indent=1)
    if a.script:
        with open(a.script, 'w') as f:
            json.dump(script_json(a.side, frames_from(a.side, spec, best[1]), DESCRIPTION[a.side]),
                      f, indent=1)
    shutil.rmtree(tmp)


if __name__ == '__main__':
    main()
