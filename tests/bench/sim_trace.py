"""One `stride sim walk` with its --record trace, for the bench scripts that measure walks from
the torso's path (walk_speed_per_direction.py, walk_straightness_per_profile.py): the episode's
JSON result and the torso's samples (t, position, yaw unwrapped)."""
import json
import math
import os
import subprocess
import tempfile


def yaw_of(q):
    w, x, y, z = q
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def walk_trace(cmd):
    """Runs `cmd` (a `stride sim walk ... --json` command line) with --record added; returns
    (result, [(t, [x, y, z], yaw unwrapped), ...]). A fall (exit 1) is a result, not an error."""
    with tempfile.TemporaryDirectory() as tmp:
        record = os.path.join(tmp, "trace.jsonl")
        out = subprocess.run(cmd + ["--record", record], capture_output=True, text=True)
        if out.returncode not in (0, 1):
            raise RuntimeError(" ".join(cmd) + ": " + out.stderr.strip())
        result = json.loads(out.stdout.strip().splitlines()[-1])
        samples = []
        with open(record) as f:
            next(f)
            for line in f:
                j = json.loads(line)
                samples.append((j["t"], j["torso"]["p"], yaw_of(j["torso"]["q"])))
    unwrapped, yaw, prev = [], 0.0, None
    for t, p, y in samples:
        yaw = y if prev is None else yaw + math.remainder(y - prev, 2 * math.pi)
        prev = y
        unwrapped.append((t, p, yaw))
    return result, unwrapped
