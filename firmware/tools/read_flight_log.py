#!/usr/bin/env python3
"""Reads a Stride flight log (stride-fw --record; format: firmware/src/recorder/FLIGHT_LOG.md).

    read_flight_log.py LOG            one line per tick: tick, motion, joint 1 position, changes
    read_flight_log.py LOG --json     a summary as one JSON object (used by the tests)

Standard library only. A log cut short (stride-fw killed) reads up to its last complete block.
"""
import json
import struct
import sys
import zlib

SERVOS = 20
PREFIX = struct.Struct("<qqqIBBHf")        # tick, sensor tick, command tick, dropped, motion...
SERVO_SENSOR = struct.Struct("<10fBB")      # pos, speed, load, V, degC, goal, P, I, D, limit...
CM730 = struct.Struct("<7fBBB")             # accel xyz, gyro xyz, V, buttons, error, health
SERVO_COMMAND = struct.Struct("<6fB")       # pos, moving speed, P, I, D, torque limit, enable
CHANGE = struct.Struct("<Hd")               # parameter index, new value
SENSOR_KEYS = ("position", "speed", "load", "voltage", "temperature", "goal_position",
               "p_gain", "i_gain", "d_gain", "torque_limit")
COMMAND_KEYS = ("position", "moving_speed", "p_gain", "i_gain", "d_gain", "torque_limit")


def decode_tick(p):
    tick, sensor_tick, command_tick, dropped, motion, flags, n, tilt = PREFIX.unpack_from(p, 0)
    at, servos, commands = PREFIX.size, [], []
    for _ in range(SERVOS):
        *v, error, status = SERVO_SENSOR.unpack_from(p, at)
        at += SERVO_SENSOR.size
        servos.append(dict(zip(SENSOR_KEYS, v), error_flags=error, health=status & 3,
                           torque_enabled=bool(status & 4)))
    *imu, buttons, error, health = CM730.unpack_from(p, at)
    at += CM730.size
    for _ in range(SERVOS):
        *v, enable = SERVO_COMMAND.unpack_from(p, at)
        at += SERVO_COMMAND.size
        commands.append(dict(zip(COMMAND_KEYS, v), torque_enable=bool(enable)))
    changes = [CHANGE.unpack_from(p, at + i * CHANGE.size) for i in range(n)]
    return dict(tick=tick, sensor_tick=sensor_tick, command_tick=command_tick,
                dropped_before=dropped, motion=motion, fallen=bool(flags & 1), tilt=tilt,
                servos=servos, accel=imu[0:3], gyro=imu[3:6], voltage=imu[6], buttons=buttons,
                cm730_error=error, cm730_health=health, commands=commands, changes=changes)


def read_log(path):
    """Returns (header, ticks, end or None, why reading stopped early or None)."""
    data = open(path, "rb").read()
    if data[:8] != b"STRIDEFL" or len(data) < 16:
        raise ValueError(f"{path}: not a Stride flight log")
    if struct.unpack_from("<I", data, 8)[0] != 1:
        raise ValueError(f"{path}: unknown flight log format version")
    header, ticks, end, at, stopped = None, [], None, 16, None
    while at < len(data):
        if len(data) - at < 8:
            stopped = f"incomplete block at byte {at}"
            break
        size, kind = struct.unpack_from("<II", data, at)
        if len(data) - at < 12 + size:
            stopped = f"incomplete block at byte {at}"
            break
        payload = data[at + 8:at + 8 + size]
        if zlib.crc32(data[at:at + 8 + size]) != struct.unpack_from("<I", data, at + 8 + size)[0]:
            stopped = f"CRC mismatch at byte {at}"
            break
        if kind == 1:
            header = json.loads(payload)
        elif kind == 2:
            ticks.append(decode_tick(payload))
        elif kind == 3:
            end = json.loads(payload)
        at += 12 + size
    if header is None:
        raise ValueError(f"{path}: no complete header block")
    return header, ticks, end, stopped


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    try:
        header, ticks, end, stopped = read_log(argv[1])
    except (OSError, ValueError) as error:
        print(f"read_flight_log: {error}", file=sys.stderr)
        return 2
    names = [p["name"] for p in header["parameters"]]
    states = header["motion_states"]
    if "--json" in argv[2:]:
        print(json.dumps({
            "firmware": header["firmware"], "hal": header["hal"],
            "robot_description_hash": header["robot_description"]["hash"],
            "ticks": len(ticks), "first_tick": ticks[0]["tick"] if ticks else None,
            "last_tick": ticks[-1]["tick"] if ticks else None,
            "dropped": sum(t["dropped_before"] for t in ticks), "end": end, "stopped": stopped,
            "last_command_positions": [c["position"] for c in ticks[-1]["commands"]] if ticks else [],
            "last_motion": states[ticks[-1]["motion"]] if ticks else None,
            "param_changes": [[t["tick"], names[i], v] for t in ticks for i, v in t["changes"]],
        }))
        return 0
    for t in ticks:
        changes = " ".join(f"{names[i]}={v:g}" for i, v in t["changes"])
        print(f"{t['tick']:8d} {states[t['motion']]:7s} {t['servos'][0]['position']:+.4f} {changes}")
    print(f"{len(ticks)} ticks" + (f"; stopped early: {stopped}" if stopped else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
