#!/usr/bin/env python3
"""Writes the seed corpus of the Dynamixel fuzz targets into tests/fuzz/corpus/<target>/.

The packets are built here, independently of Stride's codecs (protocol 1.0 checksum, protocol
2.0 CRC-16 and byte stuffing as the ROBOTIS e-manual defines them), so a codec bug cannot
shape its own seeds. Each target's input layout is described in its source file's header.
Run from anywhere; it replaces the corpus directories it writes.

    python3 tests/fuzz/make_corpus.py
"""
import pathlib
import shutil

HERE = pathlib.Path(__file__).resolve().parent
CORPUS = HERE / "corpus"

PING, READ, WRITE, REG_WRITE, ACTION, RESET, REBOOT = 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x08
STATUS, SYNC_READ, SYNC_WRITE, BULK_READ, BULK_WRITE = 0x55, 0x82, 0x83, 0x92, 0x93
BROADCAST, CM730 = 0xFE, 200


def u16(v):
    return [v & 0xFF, (v >> 8) & 0xFF]


def u32(v):
    return [(v >> (8 * i)) & 0xFF for i in range(4)]


# --- protocol 1.0 -------------------------------------------------------------------------
def v1(ident, code, params=()):
    params = list(params)
    length = len(params) + 2
    checksum = ~(ident + length + code + sum(params)) & 0xFF
    return [0xFF, 0xFF, ident, length, code] + params + [checksum]


# --- protocol 2.0 -------------------------------------------------------------------------
def crc16(data):
    crc = 0
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x8005) if crc & 0x8000 else (crc << 1)
            crc &= 0xFFFF
    return crc


def stuff(body):
    out = []
    for b in body:
        out.append(b)
        if len(out) >= 3 and out[-3:] == [0xFF, 0xFF, 0xFD]:
            out.append(0xFD)
    return out


def v2_raw(ident, body):
    """A 2.0 packet around an already stuffed (or deliberately unstuffed) body."""
    head = [0xFF, 0xFF, 0xFD, 0x00, ident] + u16(len(body) + 2) + body
    return head + u16(crc16(head))


def v2(ident, code, params=()):
    return v2_raw(ident, stuff([code] + list(params)))


def v2_status(ident, error, params=()):
    return v2_raw(ident, stuff([STATUS, error] + list(params)))


def write(target, name, data):
    folder = CORPUS / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(bytes(data))


def cat(*packets):
    return [b for p in packets for b in p]


# --- fuzz_parser_v1: [control][bytes]; chunk = 1 + (control & 0x7F) % 37, bit 7 = lazy ------
def tick_records():
    """SYNC_WRITE records as the firmware sends them each tick: P gain (28) to torque limit."""
    return cat(*[[i, 32, 0] + u16(2048) + u16(0) + u16(1023) for i in range(1, 21)])


def parser_v1():
    t = "fuzz_parser_v1"
    whole, lazy = 36, 0x80 | 36
    bulk = [0x00, 21, CM730, 30] + cat(*[[8, i, 36] for i in range(1, 21)])
    instructions = {
        "ping": v1(1, PING),
        "read_present_position": v1(5, READ, [36, 8]),
        "write_goal_position": v1(5, WRITE, [30] + u16(2048)),
        "reg_write": v1(5, REG_WRITE, [30] + u16(1000)),
        "action": v1(BROADCAST, ACTION),
        "reset": v1(5, RESET),
        "sync_write_gains_goals": v1(BROADCAST, SYNC_WRITE, [28, 8] + tick_records()),
        "bulk_read_cm730_and_servos": v1(BROADCAST, BULK_READ, bulk),
    }
    for name, p in instructions.items():
        write(t, "instruction_" + name, [whole] + p)
    train = cat(v1(CM730, 0, [0] * 21), *(v1(i, 0, u16(2048) + u16(0) + u16(0) + [150, 35])
                                       for i in range(1, 21)))
    write(t, "status_ping_reply", [whole] + v1(1, 0))
    write(t, "status_error_bits", [whole] + v1(13, 0x04, [0x24]))
    write(t, "bulk_read_reply_train", [whole] + train)
    write(t, "bulk_read_reply_train_split_1", [0] + train)
    write(t, "bulk_read_reply_train_split_7", [6] + train)
    write(t, "garbage_then_packets", [5] + [0x00, 0xFF, 0x12, 0xFF, 0xFF, 0xFF] + train[:60])
    bad = v1(3, 0, [1, 2])
    bad[-1] ^= 0x5A
    write(t, "bad_checksum_then_good", [whole] + bad + v1(4, 0, [1, 2]))
    write(t, "bad_headers", [whole] + [0xFF, 0xFF, 0xFF, 0x02, 0, 0] + [0xFF, 0xFF, 1, 1, 0]
          + v1(2, 0))
    write(t, "truncated_at_the_end", [whole] + v1(1, 0) + v1(2, 0, [1, 2, 3])[:6])
    write(t, "lazy_reader_long_train", [lazy] + train * 12)


# --- fuzz_parser_v2: [control][bytes]; chunk = 1 + (control & 0x7F) % 61, bit 7 = lazy ------
def parser_v2():
    t = "fuzz_parser_v2"
    whole, lazy = 60, 0x80 | 60
    records = cat(*[[i] + u32(2048) for i in range(1, 21)])
    bulk = cat(*[[i] + u16(132) + u16(4) for i in range(1, 21)])
    instructions = {
        "ping": v2(1, PING),  # e-manual example: FF FF FD 00 01 03 00 01 19 4E
        "read": v2(1, READ, u16(132) + u16(4)),
        "write": v2(1, WRITE, u16(116) + u32(2048)),
        "reg_write": v2(1, REG_WRITE, u16(116) + u32(1024)),
        "action": v2(BROADCAST, ACTION),
        "factory_reset": v2(1, RESET, [0x02]),
        "reboot": v2(1, REBOOT),
        "sync_read": v2(BROADCAST, SYNC_READ, u16(132) + u16(4) + list(range(1, 21))),
        "sync_write": v2(BROADCAST, SYNC_WRITE, u16(116) + u16(4) + records),
        "bulk_read": v2(BROADCAST, BULK_READ, bulk),
        "bulk_write": v2(BROADCAST, BULK_WRITE, [1] + u16(116) + u16(4) + u32(2048)),
        "stuffed_params": v2(1, WRITE, u16(116) + [0xFF, 0xFF, 0xFD, 0x00, 0xFF, 0xFF, 0xFD]),
        "params_like_a_header": v2(1, WRITE, u16(116) + [0xFF, 0xFF, 0x00, 0xFF, 0xFF, 0xFF]),
    }
    for name, p in instructions.items():
        write(t, "instruction_" + name, [whole] + p)
    train = cat(*[v2_status(i, 0, u32(2048 + i)) for i in range(1, 21)])
    write(t, "status_ping_reply", [whole] + v2_status(1, 0, [0x06, 0x04, 0x26]))
    write(t, "status_alert_and_error", [whole] + v2_status(13, 0x80 | 0x07))
    write(t, "status_stuffed", [whole] + v2_status(2, 0, [0xFF, 0xFF, 0xFD, 0xFD, 1]))
    write(t, "status_without_error_byte", [whole] + v2_raw(3, [STATUS]) + v2_status(4, 0))
    write(t, "body_ends_in_unstuffed_header", [whole] + v2_raw(5, [WRITE, 0xFF, 0xFF, 0xFD]))
    write(t, "unstuffed_header_inside_body", [whole] + v2_raw(5, [WRITE, 0xFF, 0xFF, 0xFD, 0, 1]))
    write(t, "sync_read_reply_train", [whole] + train)
    write(t, "sync_read_reply_train_split_1", [0] + train)
    write(t, "sync_read_reply_train_split_13", [12] + train)
    bad = v2_status(6, 0, [1])
    bad[-2] ^= 0x33
    write(t, "bad_crc_then_good", [whole] + bad + v2_status(7, 0, [1]))
    bad_headers = ([0xFF, 0xFF, 0xFD, 0x00, 0xFD, 3, 0, 1, 0, 0]
                   + [0xFF, 0xFF, 0xFD, 0x00, 0xFF, 3, 0, 1, 0, 0]
                   + [0xFF, 0xFF, 0xFD, 0x00, 1, 2, 0, 1, 0]
                   + [0xFF, 0xFF, 0xFD, 0x00, 1] + u16(2000) + [1])
    write(t, "bad_headers", [whole] + bad_headers + v2_status(8, 0))
    write(t, "garbage_then_packets", [7] + [0xFF, 0xFF, 0xFD, 0x01, 0xFF, 0xFF, 0x00] + train[:80])
    write(t, "truncated_at_the_end", [whole] + v2_status(1, 0) + v2_status(2, 0, [1, 2])[:9])
    long_write = v2(1, WRITE, u16(0) + [i & 0xFF for i in range(900)])
    write(t, "long_packet", [whole] + long_write)
    write(t, "lazy_reader_long_train", [lazy] + train * 9)
    write(t, "compaction_behind_long_packets", [whole] + long_write
          + v2(2, WRITE, u16(0) + [0] * 200) + train[:200])


# --- fuzz_codec: [selector][id][a0 a1][b0 b1][c][s0 s1][rest] ----------------------------
def codec():
    t = "fuzz_codec"
    entries = cat(*[[i] + u16(132) + u16(4) for i in range(1, 6)])
    rest_for = {8: [1, 5, 0, 2, 6, 0], 9: [1] + u16(36) + u16(8) + [200] + u16(30) + u16(21)}
    for which in range(10):  # protocol 1.0 encoders
        rest = rest_for.get(which, [0x10, 0x20, 0xFF])
        args = [1, 30, 0, 2, 0, 0x24] if which != 8 else [BROADCAST, 30, 0, 2, 0, 0]
        write(t, "v1_encoder_%d" % which, [which] + args + u16(0) + rest)
    write(t, "v1_sync_write_no_length", [8, 0, 30, 0, 0, 0, 0] + u16(0) + [1, 2])
    write(t, "v1_sync_write_torn_record", [8, 0, 30, 0, 2, 0, 0] + u16(0) + [1, 2])
    write(t, "v1_status_small_buffer", [1, 7, 0, 0, 0, 0, 0x20] + u16(8) + [1, 2, 3])
    write(t, "v1_bulk_read_length_too_big", [9, 0, 0, 0, 0, 0, 0] + u16(0) + [1, 36, 0, 0, 1])
    write(t, "v1_bulk_read_address_too_big", [9, 0, 0, 0, 0, 0, 0] + u16(0) + [1, 0, 1, 8, 0])
    write(t, "v1_bulk_read_too_many_entries", [9, 0, 0, 0, 0, 0, 0] + u16(0)
          + [1, 36, 0, 8, 0] * 85)
    write(t, "v1_bulk_read_small_buffer", [9, 0, 0, 0, 0, 0, 0] + u16(9) + [1, 36, 0, 8, 0])
    write(t, "v1_too_many_params", [0, 1, 0, 0, 0, 0, 3] + u16(0) + [7] * 254)
    rest_for = {10: [1] + u32(2048) + [2] + u32(1024), 11: entries, 9: [1, 2, 3]}
    for which in range(12):  # protocol 2.0 encoders
        rest = rest_for.get(which, [0xFF, 0xFF, 0xFD, 0x00])
        args = [1] + u16(116) + u16(4) + [0x02]
        write(t, "v2_encoder_%d" % which, [0x80 | which] + args + u16(0) + rest)
    write(t, "v2_stuffing_fits_exactly", [0x80, 1, 0, 0, 0, 0, 3] + u16(14) + [0xFF, 0xFF, 0xFD])
    write(t, "v2_stuffing_byte_does_not_fit", [0x80, 1, 0, 0, 0, 0, 3] + u16(13)
          + [0xFF, 0xFF, 0xFD])
    write(t, "v2_sync_write_no_length", [0x8A, 0, 116, 0, 0, 0, 0] + u16(0) + [1, 2])
    write(t, "v2_sync_write_torn_record", [0x8A, 0, 116, 0, 4, 0, 0] + u16(0) + [1, 2])
    write(t, "v2_read_head_does_not_fit", [0x83, 1, 116, 0, 4, 0, 0] + u16(11))
    write(t, "v2_buffer_below_minimum", [0x82, 1, 0, 0, 0, 0, 0] + u16(9))
    write(t, "v2_bulk_read_too_many_entries", [0x8B, 0, 0, 0, 0, 0, 0] + u16(0)
          + [1, 0, 0, 4, 0] * 205)
    write(t, "v2_status_buffer_of_10", [0x81, 1, 0, 0, 0, 0, 0] + u16(10) + [])
    write(t, "v2_status_too_long", [0x81, 1, 0, 0, 0, 0, 0] + u16(0) + [0xFF, 0xFF, 0xFD] * 340)


# --- virtual buses: [flags][silent id][overheat id][chunk][host bytes] ---------------------
# flags: 0x01 drop 30 %, 0x02 corrupt 30 %, 0x04 silent, 0x08 overheat, 0x10 faults start
# after the first read cycle, 0x20 wall-clock time, 0x40 MX-64 and MX-106 mixed; chunk 0 = all
# bytes in one read.
def virtual_bus():
    t = "fuzz_virtual_bus"
    bulk = [0x00, 21, CM730, 30] + cat(*[[8, i, 36] for i in range(1, 21)])
    startup = cat(v1(CM730, PING), v1(CM730, WRITE, [24, 1]), v1(BROADCAST, WRITE, [5, 0]),
                  v1(BROADCAST, WRITE, [16, 1]), *(v1(i, PING) for i in range(1, 21)),
                  *(v1(i, READ, [0, 2]) for i in range(1, 21)))
    tick = cat(v1(BROADCAST, SYNC_WRITE, [28, 8] + tick_records()), v1(BROADCAST, BULK_READ, bulk))
    write(t, "startup", [0, 0, 0, 0] + startup)
    write(t, "ticks", [0, 0, 0, 0] + tick * 3)
    write(t, "ticks_split_5", [0, 0, 0, 5] + tick * 2)
    write(t, "ticks_with_faults", [0x1F, 7, 13, 0] + cat(v1(13, WRITE, [24, 1])) + tick * 3)
    requests = cat(
        v1(3, READ, [36, 8]), v1(3, READ, [70, 10]), v1(3, READ, [1]),
        v1(3, WRITE, [30] + u16(5000)), v1(3, WRITE, [6] + u16(1000) + u16(3000)),
        v1(3, WRITE, [30] + u16(500)), v1(3, WRITE, [80, 1]), v1(3, WRITE, [30]),
        v1(3, REG_WRITE, [30] + u16(1500)), v1(3, ACTION), v1(3, ACTION), v1(3, REG_WRITE, [30]),
        v1(3, RESET), v1(3, 0x44), v1(3, WRITE, [16, 0]), v1(3, READ, [36, 2]),
        v1(3, WRITE, [16, 1]), v1(3, READ, [36, 2]), v1(3, WRITE, [36, 0, 0]),
        v1(BROADCAST, WRITE, [25, 1]), v1(BROADCAST, REG_WRITE, [25, 0]),
        v1(BROADCAST, ACTION), v1(BROADCAST, RESET), v1(BROADCAST, SYNC_WRITE, [30, 2, 1]),
        v1(BROADCAST, BULK_READ, [0x00, 100, 1, 30]), v1(BROADCAST, BULK_READ, [0x00, 2]),
        v1(CM730, READ, [38, 12]), v1(99, PING))
    write(t, "requests_and_errors", [0, 0, 0, 0] + requests)
    bad = v1(4, PING)
    bad[-1] ^= 0x01
    write(t, "bad_checksum", [0, 0, 0, 0] + bad + v1(4, PING))
    write(t, "overheat_shutdown", [0x08, 0, 9, 0] + v1(9, WRITE, [24, 1]) + v1(9, READ, [43, 1])
          + v1(9, WRITE, [24, 1]))
    write(t, "silent_in_bulk_read", [0x04, 5, 0, 0] + v1(BROADCAST, BULK_READ, bulk))
    write(t, "wall_clock_mixed_models", [0x60, 0, 0, 0] + startup + tick)


def virtual_bus_v2():
    t = "fuzz_virtual_bus_v2"
    ids = list(range(1, 21))
    tick = cat(v2(BROADCAST, SYNC_WRITE, u16(116) + u16(4) + cat(*[[i] + u32(2048) for i in ids])),
               v2(BROADCAST, SYNC_READ, u16(132) + u16(4) + ids))
    bulk = v2(BROADCAST, BULK_READ, cat(*[[i] + u16(132) + u16(4) for i in ids]))
    write(t, "scan", [0, 0, 0, 0] + v2(BROADCAST, PING) + cat(*[v2(i, PING) for i in ids])
          + cat(*[v2(i, READ, u16(0) + u16(2)) for i in ids]))
    write(t, "ticks", [0, 0, 0, 0] + tick * 3 + bulk)
    write(t, "ticks_split_9", [0, 0, 0, 9] + tick * 2)
    write(t, "ticks_with_faults", [0x1F, 7, 13, 0] + v2(13, WRITE, u16(64) + [1]) + tick * 4
          + bulk)
    requests = cat(
        v2(3, READ, u16(132) + u16(4)), v2(3, READ, u16(140) + u16(20)), v2(3, READ, u16(1)),
        v2(3, WRITE, u16(116) + u32(5000)), v2(3, WRITE, u16(48) + u32(3000)),
        v2(3, WRITE, u16(116) + u32(3500)), v2(3, WRITE, u16(117) + [1]),
        v2(3, WRITE, u16(132) + u32(0)), v2(3, WRITE, u16(200) + [1]), v2(3, WRITE, u16(8)),
        v2(3, REG_WRITE, u16(116) + u32(1500)), v2(3, ACTION), v2(3, ACTION),
        v2(3, REG_WRITE, u16(116)), v2(3, REBOOT), v2(3, 0x44),
        v2(3, WRITE, u16(64) + [1]), v2(3, WRITE, u16(8) + [3]), v2(3, WRITE, u16(64) + [0]),
        v2(3, WRITE, u16(8) + [3]), v2(3, RESET, [0x02]), v2(3, RESET, [0x01]),
        v2(3, RESET, [0x00]), v2(3, RESET), v2(BROADCAST, RESET, [0xFF]),
        v2(3, WRITE, u16(68) + [0]), v2(3, READ, u16(132) + u16(4)), v2(3, PING),
        v2(3, WRITE, u16(68) + [1]), v2(3, WRITE, u16(11) + [4]),
        v2(3, WRITE, u16(116) + u32(3500)), v2(3, RESET, [0xFF]), v2(1, PING),
        v2(BROADCAST, WRITE, u16(65) + [1]), v2(BROADCAST, READ, u16(0) + u16(2)),
        v2(BROADCAST, SYNC_READ, u16(0)), v2(BROADCAST, SYNC_WRITE, u16(116) + u16(0)),
        v2(4, SYNC_READ, u16(0) + u16(2) + [4]), v2(BROADCAST, SYNC_READ, u16(146) + u16(4) + [4]),
        v2(BROADCAST, BULK_READ, [4] + u16(146) + u16(4)), v2(4, BULK_READ, [4] + u16(0) + u16(2)),
        v2_status(4, 0), v2(99, PING))
    write(t, "requests_and_errors", [0, 0, 0, 0] + requests)
    bad = v2(4, PING)
    bad[-1] ^= 0x11
    write(t, "bad_crc", [0, 0, 0, 0] + bad + v2(4, PING))
    write(t, "overheat_shutdown", [0x08, 0, 9, 0] + v2(9, WRITE, u16(64) + [1])
          + v2(9, READ, u16(70) + u16(1)) + v2(9, WRITE, u16(64) + [1]))
    write(t, "silent_in_sync_read", [0x04, 5, 0, 0] + tick)
    write(t, "wall_clock_mixed_models", [0x60, 0, 0, 0] + v2(BROADCAST, PING) + tick + bulk)


def main():
    for target in ("fuzz_parser_v1", "fuzz_parser_v2", "fuzz_codec", "fuzz_virtual_bus",
                   "fuzz_virtual_bus_v2"):
        shutil.rmtree(CORPUS / target, ignore_errors=True)
    parser_v1()
    parser_v2()
    codec()
    virtual_bus()
    virtual_bus_v2()


if __name__ == "__main__":
    main()
