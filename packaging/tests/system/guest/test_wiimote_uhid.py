#!/usr/bin/env python3
"""Host-side tests of wiimote_uhid.py (the VM test's emulated Wii Remote): no /dev/uhid needed.

    python3 -m unittest packaging/tests/system/guest/test_wiimote_uhid.py   (from the checkout)

They cover the uhid event layouts, the report descriptor, the remote's answers to what Mallet
(src/input/wiimote/wiimote_device.cpp, ir_startup.cpp) and the kernel's hid-wiimote send, the
data reports in each mode, the scripted paths against the kiosk's calibration rules, and the
emulator's loop against a fake /dev/uhid (a SOCK_SEQPACKET socketpair: one event per message).
Where a built mallet exists (MALLET=path, or build/*/mallet), every report the emulator makes is
also decoded by Mallet's own parser (`mallet wiimote decode`), and the calibration points are
fitted by `mallet calibrate fit`.
"""

import contextlib
import glob
import io
import math
import os
import socket
import subprocess
import sys
import tempfile
import threading
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import wiimote_uhid as wu  # noqa: E402

ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))


def find_mallet():
    env = os.environ.get("MALLET")
    if env:
        return env if os.access(env, os.X_OK) else None
    for candidate in sorted(glob.glob(os.path.join(ROOT, "build", "*", "mallet"))):
        if os.access(candidate, os.X_OK):
            return candidate
    return None


MALLET = find_mallet()


def h(text):
    return bytes.fromhex(text)


def pad22(report):
    return report + bytes(22 - len(report))


# What Mallet sends on connect (wiimote_device.cpp try_connect, then ir_startup.cpp), built
# here by hand from those files: LEDs (player 1), a status request, then the IR start-up.
WII1 = (h("0200007101006400fe"), h("fd05"))   # core/ir_camera_settings.hpp
WII3 = (h("020000710100aa0064"), h("6303"))


def mallet_startup(block1, block2, mode=0x33, ir_format=3, rumble=0):
    r = rumble
    return [
        bytes((0x13, 0x06 | r)),
        bytes((0x1A, 0x06 | r)),
        pad22(bytes((0x16, 0x04 | r, 0xB0, 0x00, 0x30, 1, 0x01))),
        pad22(bytes((0x16, 0x04 | r, 0xB0, 0x00, 0x00, 9)) + block1),
        pad22(bytes((0x16, 0x04 | r, 0xB0, 0x00, 0x1A, 2)) + block2),
        pad22(bytes((0x16, 0x04 | r, 0xB0, 0x00, 0x33, 1, ir_format))),
        pad22(bytes((0x16, 0x04 | r, 0xB0, 0x00, 0x30, 1, 0x08))),
        bytes((0x12, 0x06 | r, mode)),
    ]


MALLET_CONNECT = [h("1110"), h("1500")] + mallet_startup(*WII3)

# What hid-wiimote sends (drivers/hid/hid-wiimote-core.c, -modules.c): the status request of
# its detection, LED 1, its 4-second extension / Motion Plus poll, its IR node's open (basic
# IR, sensitivity "wii3", DRM 0x36 not continuous) and close.
KERNEL_DETECT = h("1500")
KERNEL_LED1 = h("1110")
KERNEL_POLL = [h("1704a400fa0006"), pad22(h("1604a600f00155")), h("1704a600fa0006")]
KERNEL_IR_OPEN = [h("1306"), h("1a06"), pad22(h("1604b000300101")), pad22(h("1604b0000009") + WII3[0]),
                  pad22(h("1604b0001a02") + WII3[1]), pad22(h("1604b000330101")),
                  pad22(h("1604b000300108")), h("120036")]
KERNEL_IR_CLOSE = [h("1300"), h("1a00"), h("120030")]

INPUT_LENGTHS = {0x20: 7, 0x21: 22, 0x22: 5, 0x30: 3, 0x31: 6, 0x32: 11, 0x33: 18, 0x34: 22, 0x35: 22,
                 0x36: 22, 0x37: 22, 0x3D: 22, 0x3E: 22, 0x3F: 22}


def decode_ir(report):
    """The dots as Mallet's parser reads them (src/input/wiimote/reports.cpp), written again here."""
    rid = report[0]
    if rid == 0x33:
        ir = report[6:18]
        out = []
        for i in range(4):
            b = ir[3 * i:3 * i + 3]
            x = b[0] | ((b[2] >> 4) & 3) << 8
            y = b[1] | ((b[2] >> 6) & 3) << 8
            out.append(None if y > 767 else (x, y, b[2] & 0x0F))
        return out
    ir = report[3:13] if rid == 0x36 else report[6:16]
    out = []
    for p in range(2):
        b = ir[5 * p:5 * p + 5]
        x1, y1 = b[0] | ((b[2] >> 4) & 3) << 8, b[1] | ((b[2] >> 6) & 3) << 8
        x2, y2 = b[3] | (b[2] & 3) << 8, b[4] | ((b[2] >> 2) & 3) << 8
        out.append(None if y1 > 767 else (x1, y1, -1))
        out.append(None if y2 > 767 else (x2, y2, -1))
    return out


def run_all(model, reports):
    out = []
    for r in reports:
        out.extend(model.handle_output(r))
    return out


class UhidLayout(unittest.TestCase):
    """struct uhid_event as Linux 6.1's include/uapi/linux/uhid.h has it."""

    def test_event_numbers(self):
        self.assertEqual((wu.UHID_DESTROY, wu.UHID_START, wu.UHID_STOP, wu.UHID_OPEN, wu.UHID_CLOSE, wu.UHID_OUTPUT),
                         (1, 2, 3, 4, 5, 6))
        self.assertEqual((wu.UHID_GET_REPORT, wu.UHID_GET_REPORT_REPLY, wu.UHID_CREATE2, wu.UHID_INPUT2,
                          wu.UHID_SET_REPORT, wu.UHID_SET_REPORT_REPLY), (9, 10, 11, 12, 13, 14))

    def test_event_size_is_the_create2_union_member(self):
        # __u32 type + name[128] phys[64] uniq[64] rd_size bus vendor product version country rd_data[4096]
        self.assertEqual(wu.EVENT_SIZE, 4 + 128 + 64 + 64 + 2 + 2 + 4 * 4 + 4096)
        self.assertEqual(wu.EVENT_SIZE, 4376)

    def test_create2_fields_at_their_offsets(self):
        rd = wu.report_descriptor()
        ev = wu.pack_create2("Nintendo RVL-CNT-01", "00:00:00:00:00:00", "00:19:1d:4d:4c:01", rd)
        self.assertEqual(len(ev), wu.EVENT_SIZE)
        self.assertEqual(int.from_bytes(ev[0:4], "little"), 11)
        self.assertEqual(ev[4:4 + 19], b"Nintendo RVL-CNT-01")
        self.assertEqual(ev[4 + 19], 0)
        self.assertEqual(ev[132:132 + 17], b"00:00:00:00:00:00")
        self.assertEqual(ev[196:196 + 17], b"00:19:1d:4d:4c:01")
        self.assertEqual(int.from_bytes(ev[260:262], "little"), len(rd))      # rd_size
        self.assertEqual(int.from_bytes(ev[262:264], "little"), 0x05)         # bus: Bluetooth
        self.assertEqual(int.from_bytes(ev[264:268], "little"), 0x057E)       # vendor
        self.assertEqual(int.from_bytes(ev[268:272], "little"), 0x0306)       # product
        self.assertEqual(ev[280:280 + len(rd)], rd)                          # rd_data
        etype, f = wu.unpack_event(ev)
        self.assertEqual((etype, f["name"], f["bus"], f["vendor"], f["product"], f["descriptor"]),
                         (wu.UHID_CREATE2, "Nintendo RVL-CNT-01", 5, 0x057E, 0x0306, rd))

    def test_input2_output_and_replies(self):
        ev = wu.pack_input2(h("2000000000c8")[:6] + b"\x00")
        self.assertEqual(len(ev), wu.EVENT_SIZE)
        self.assertEqual(int.from_bytes(ev[0:4], "little"), 12)
        self.assertEqual(int.from_bytes(ev[4:6], "little"), 7)               # __u16 size
        self.assertEqual(ev[6:13], h("2000000000c8") + b"\x00")              # then data
        out = wu.pack_output_event(h("120633"))
        self.assertEqual(int.from_bytes(out[4100:4102], "little"), 3)       # size after data[4096]
        self.assertEqual(out[4102], wu.UHID_OUTPUT_REPORT)                   # rtype
        self.assertEqual(wu.unpack_event(out), (wu.UHID_OUTPUT, {"data": h("120633"), "rtype": 1}))
        self.assertEqual(wu.unpack_event(out[:4103])[1]["data"], h("120633"))  # a short read is zero-extended
        r = wu.pack_get_report_reply(0x01020304, 5)
        self.assertEqual(r[:12], h("0a000000" "04030201" "0500" "0000"))
        r = wu.pack_set_report_reply(7, 0)
        self.assertEqual(r[:10], h("0e000000" "07000000" "0000"))
        self.assertEqual(wu.pack_destroy()[:4], h("01000000"))
        get = h("09000000" "2a000000" "20" "02")
        self.assertEqual(wu.unpack_event(get), (wu.UHID_GET_REPORT, {"id": 42, "rnum": 0x20, "rtype": 2}))
        setr = h("0d000000" "2b000000" "12" "01" "0300") + h("120633")
        self.assertEqual(wu.unpack_event(setr)[1], {"id": 43, "rnum": 0x12, "rtype": 1, "data": h("120633")})
        start = h("02000000") + (1).to_bytes(8, "little")
        self.assertEqual(wu.unpack_event(start), (wu.UHID_START, {"dev_flags": 1}))


class Descriptor(unittest.TestCase):
    def items(self):
        d = wu.report_descriptor()
        i, out = 0, []
        while i < len(d):
            prefix = d[i]
            size = {0: 0, 1: 1, 2: 2, 3: 4}[prefix & 3]
            out.append((prefix & 0xFC, int.from_bytes(d[i + 1:i + 1 + size], "little")))
            i += 1 + size
        self.assertEqual(i, len(d))
        return out

    def test_every_report_declared_with_its_length(self):
        reports, rid, count, size = {}, None, None, None
        for tag, value in self.items():
            if tag == 0x84:
                rid = value
            elif tag == 0x94:
                count = value
            elif tag == 0x74:
                size = value
            elif tag in (0x80, 0x90):
                reports[(rid, "in" if tag == 0x80 else "out")] = count * size // 8
        for rid, n in wu.INPUT_PAYLOAD.items():
            self.assertEqual(reports[(rid, "in")] + 1, INPUT_LENGTHS[rid], "input 0x%02x" % rid)
        self.assertEqual({r for r, d in reports if d == "in"}, set(INPUT_LENGTHS))
        self.assertEqual({r for r, d in reports if d == "out"}, set(range(0x10, 0x1B)))
        self.assertEqual(reports[(0x16, "out")] + 1, 22)   # a write: id, flags, 3 address, size, 16 data
        self.assertEqual(reports[(0x17, "out")] + 1, 7)

    def test_collections_balance(self):
        tags = [t for t, _ in self.items()]
        self.assertEqual(tags.count(0xA0), tags.count(0xC0))
        self.assertLessEqual(len(wu.report_descriptor()), wu.HID_MAX_DESCRIPTOR_SIZE)


class MalletConnect(unittest.TestCase):
    """The remote's answers to exactly what Mallet sends on connect."""

    def setUp(self):
        self.log = []
        self.m = wu.WiimoteModel(log=self.log.append)

    def test_connect_and_ir_startup(self):
        m = self.m
        self.assertEqual(m.handle_output(h("1110")), [])                      # LEDs: no ack asked
        self.assertEqual(m.leds, 1)
        self.assertEqual(m.handle_output(h("1500")), [h("20000010" "0000c8")])  # LED 1, battery 0xc8
        startup = mallet_startup(*WII3)
        self.assertEqual(m.handle_output(startup[0]), [h("2200001300")])
        self.assertFalse(m.camera_sending)
        self.assertEqual(m.handle_output(startup[1]), [h("2200001a00")])
        for write in startup[2:7]:
            self.assertEqual(m.handle_output(write), [h("2200001600")])
        self.assertTrue(m.camera_sending)
        self.assertEqual(m.sensitivity_name(), "wii3")
        self.assertEqual(m.camera_format, 3)
        self.assertEqual(m.startups, 0)
        self.assertEqual(m.handle_output(startup[7]), [h("2200001200")])      # 12 06 33: acked
        self.assertEqual((m.mode, m.continuous, m.reporting), (0x33, True, True))
        self.assertEqual((m.startups, m.switches), (1, 0))                   # after a connect
        self.assertTrue(any("IR start-up #1 complete, after a connect" in line for line in self.log))
        self.assertEqual(m.handle_output(h("1500"))[0][3] & 0x08, 0x08)       # status: IR on

    def test_data_reports_carry_the_dot(self):
        run_all(self.m, MALLET_CONNECT)
        r = self.m.data_report([(700, 600, 4)])
        self.assertEqual(len(r), 18)
        self.assertEqual(r[:6], h("330000") + wu.ACCEL_AT_REST)
        self.assertEqual(decode_ir(r), [(700, 600, 4), None, None, None])
        self.assertEqual(decode_ir(self.m.data_report([(1023, 767, 15)]))[0], (1023, 767, 15))
        self.assertEqual(decode_ir(self.m.data_report([])), [None] * 4)
        self.assertEqual(decode_ir(self.m.data_report([(0, 0, 1), None, (512, 384, 2), (256, 700, 3)])),
                         [(0, 0, 1), None, (512, 384, 2), (256, 700, 3)])
        self.assertEqual(self.m.data_report([(5, 5, 4)]), self.m.data_report([(5, 5, 4)]))  # continuous: every tick

    def test_ir_report(self):
        run_all(self.m, MALLET_CONNECT)
        self.assertEqual(decode_ir(self.m.ir_report(300, 200)), [(300, 200, 4), None, None, None])

    def test_sensitivity_switches_are_counted_apart_from_connects(self):
        run_all(self.m, MALLET_CONNECT)
        run_all(self.m, mallet_startup(*WII1))   # the tuner's first preset
        self.assertEqual(self.m.sensitivity_name(), "wii1")
        run_all(self.m, mallet_startup(*WII1))   # ... chosen
        self.assertEqual((self.m.startups, self.m.switches), (3, 2))
        run_all(self.m, MALLET_CONNECT)          # a reconnect: not a switch
        self.assertEqual((self.m.startups, self.m.switches), (4, 2))

    def test_basic_mode(self):
        run_all(self.m, [h("1110"), h("1500")] + mallet_startup(*WII3, mode=0x36, ir_format=1))
        r = self.m.data_report([(1000, 700, 4), (3, 4, 4)])
        self.assertEqual((r[0], len(r)), (0x36, 22))
        self.assertEqual(decode_ir(r), [(1000, 700, -1), (3, 4, -1), None, None])

    def test_rumble_bit_in_every_report(self):
        run_all(self.m, MALLET_CONNECT)
        self.m.handle_output(h("1111"))
        self.assertTrue(self.m.rumble)
        self.m.handle_output(h("1110"))
        self.assertFalse(self.m.rumble)

    def test_camera_not_sending_means_no_dots(self):
        run_all(self.m, MALLET_CONNECT)
        self.m.handle_output(pad22(h("1604b000300101")))   # camera on, not sending (a restart)
        self.assertEqual(decode_ir(self.m.data_report([(10, 10, 4)])), [None] * 4)
        self.m.handle_output(h("1a02"))                      # IR logic off, ack asked
        self.m.handle_output(pad22(h("1604b000300108")))
        self.assertFalse(self.m.camera_sending)
        self.m.handle_output(h("1a04"))
        self.assertEqual(decode_ir(self.m.data_report([(10, 10, 4)]))[0], (10, 10, 4))

    def test_format_mismatch_sends_no_dots_and_says_so(self):
        run_all(self.m, MALLET_CONNECT)
        self.m.handle_output(pad22(h("1604b000330101")))     # the camera in basic format, 0x33 asked
        self.assertEqual(decode_ir(self.m.data_report([(10, 10, 4)])), [None] * 4)
        self.assertTrue(any("format 1" in line for line in self.log))

    def test_needs_sensitivity(self):
        m = wu.WiimoteModel(needs_sensitivity="wii2")
        run_all(m, [h("1110"), h("1500")] + mallet_startup(*WII1))
        self.assertEqual(decode_ir(m.data_report([(10, 10, 4)])), [None] * 4)
        run_all(m, mallet_startup(*WII3))
        self.assertEqual(decode_ir(m.data_report([(10, 10, 4)]))[0], (10, 10, 4))


class ProtocolRules(unittest.TestCase):
    def setUp(self):
        self.m = wu.WiimoteModel()

    def test_ack_bit(self):
        self.assertEqual(self.m.handle_output(h("1304")), [])
        self.assertEqual(self.m.handle_output(h("1306")), [h("2200001300")])
        self.assertEqual(self.m.handle_output(h("1112")), [h("2200001100")])
        self.assertEqual(self.m.handle_output(h("1406")), [h("2200001400")])
        self.assertEqual(self.m.handle_output(h("120730")), [h("2200001200")])  # rumble + ack + continuous
        self.assertEqual(self.m.handle_output(h("120299")), [h("2200001203")])  # no such mode: error 3
        self.assertEqual(self.m.mode, 0x30)

    def test_writes_are_always_acked(self):
        self.assertEqual(self.m.handle_output(pad22(h("1604b000330103"))), [h("2200001600")])
        self.assertEqual(self.m.handle_output(pad22(h("1600000020" "0411223344"))), [h("2200001600")])  # EEPROM
        self.assertEqual(self.m.handle_output(pad22(h("1604ff000001aa"))), [h("2200001608")])  # no memory
        self.assertEqual(self.m.handle_output(pad22(h("1604b0000011"))), [h("2200001603")])    # 17 bytes: bad

    def test_reads(self):
        self.m.handle_output(pad22(h("1604b0000009") + WII3[0]))
        (r,) = self.m.handle_output(h("1704b000000009"))
        self.assertEqual(r[:6], h("210000" "80" "0000"))     # 9 bytes (size-1 = 8 << 4), error 0, at ..0000
        self.assertEqual(r[6:15], WII3[0])
        self.assertEqual(len(r), 22)
        chunks = self.m.handle_output(h("1700000000" "0020"))   # 32 bytes of EEPROM: two chunks
        self.assertEqual([c[3:6] for c in chunks], [h("f00000"), h("f00010")])
        self.assertEqual(chunks[1][6 + 6:6 + 16], h("808080009a9a9a004000"))  # accel calibration at 0x16
        (bad,) = self.m.handle_output(h("1700ffff000010"))
        self.assertEqual(bad[3:6], h("08ff00"))

    def test_status_resets(self):
        m = wu.WiimoteModel(status_resets="unsolicited")
        run_all(m, MALLET_CONNECT)
        m.handle_output(h("1500"))
        self.assertIsNotNone(m.data_report([]))                 # solicited: reports go on
        self.assertEqual(m.unsolicited_status()[0], 0x20)
        self.assertIsNone(m.data_report([]))                    # unsolicited: stopped ...
        m.handle_output(h("120633"))
        self.assertIsNotNone(m.data_report([]))                 # ... until 0x12
        strict = wu.WiimoteModel(status_resets="all")
        run_all(strict, MALLET_CONNECT)
        strict.handle_output(h("1500"))
        self.assertIsNone(strict.data_report([]))

    def test_on_change_mode_sends_only_changes(self):
        self.assertEqual(self.m.data_report([]), h("300000"))   # a fresh remote: 0x30, once
        self.assertIsNone(self.m.data_report([]))
        self.m.handle_output(h("120031"))
        self.assertEqual(self.m.data_report([]), h("310000") + wu.ACCEL_AT_REST)
        self.assertIsNone(self.m.data_report([]))

    def test_every_mode_has_its_length(self):
        for mode in wu.DATA_MODES:
            self.m.handle_output(bytes((0x12, 0x04, mode)))
            r = self.m.data_report([(1, 2, 3)])
            self.assertEqual(len(r), INPUT_LENGTHS[r[0]], "mode 0x%02x" % mode)
            self.assertIn(r[0], (mode, 0x3E, 0x3F))

    def test_unknown_and_short_reports_are_ignored(self):
        self.assertEqual(self.m.handle_output(h("50")), [])
        self.assertEqual(self.m.handle_output(h("12")), [])
        self.assertEqual(self.m.handle_output(h("1204")), [])
        self.assertEqual(self.m.handle_output(b""), [])

    def test_reset_forgets_but_keeps_counts(self):
        run_all(self.m, MALLET_CONNECT)
        self.m.reset()
        self.assertEqual((self.m.mode, self.m.camera_sending, self.m.leds, self.m.startups), (0x30, False, 0, 1))


class KernelDriver(unittest.TestCase):
    """What hid-wiimote sends at bind time, every 4 s, and when its IR node is opened."""

    def setUp(self):
        self.m = wu.WiimoteModel()

    def test_detection_and_leds(self):
        (status,) = self.m.handle_output(KERNEL_DETECT)
        self.assertEqual(status[3] & 0x02, 0)          # no extension: the driver reads no extension id
        self.assertEqual(len(status), 7)               # its handler needs more than 6 bytes after the id
        self.assertEqual(self.m.handle_output(KERNEL_LED1), [])
        self.assertEqual(self.m.handle_output(h("120030")), [])   # its DRM after a status: not acked

    def test_extension_and_motion_plus_poll(self):
        read_ext, write_mp, read_mp = (self.m.handle_output(r) for r in KERNEL_POLL)
        # The driver matches a read's answer by the low 16 bits of its address, and takes any
        # error as "nothing there" (wiimote_cmd_read returns -EIO).
        self.assertEqual(read_ext, [h("210000" "07" "00fa") + bytes(16)])
        self.assertEqual(write_mp, [h("2200001607")])
        self.assertEqual(read_mp, [h("210000" "07" "00fa") + bytes(16)])

    def test_the_poll_is_logged_thinly(self):
        lines = []
        m = wu.WiimoteModel(log=lines.append)
        for _ in range(30):
            run_all(m, KERNEL_POLL)
        polls = [line for line in lines if line.startswith("<- 17 04 a4")]
        self.assertEqual(len(polls), 3 + 2)   # the first three, then the 15th and 30th
        self.assertIn("seen 30 times", polls[-1])

    def test_absent_error_option(self):
        m = wu.WiimoteModel(absent_error=0)
        read_ext, write_mp, _ = (m.handle_output(r) for r in KERNEL_POLL)
        self.assertEqual(read_ext, [h("210000" "50" "00fa") + b"\xff" * 6 + bytes(10)])  # 6 bytes of ff: nothing
        self.assertEqual(write_mp, [h("2200001600")])

    def test_ir_node_open_and_close(self):
        answers = run_all(self.m, KERNEL_IR_OPEN)
        self.assertEqual(answers, [h("2200001300"), h("2200001a00")] + [h("2200001600")] * 5)
        self.assertEqual((self.m.mode, self.m.continuous, self.m.camera_format), (0x36, False, 1))
        self.assertEqual(self.m.startups, 0)            # not Mallet's: the kernel's DRM is not continuous
        r = self.m.data_report([(100, 200, 4)])
        self.assertEqual(decode_ir(r)[0], (100, 200, -1))
        self.assertIsNone(self.m.data_report([(100, 200, 4)]))        # on change only
        self.assertIsNotNone(self.m.data_report([(101, 200, 4)]))
        run_all(self.m, KERNEL_IR_CLOSE)
        self.assertFalse(self.m.camera_sending)
        self.assertEqual(self.m.mode, 0x30)

    def test_kernel_then_mallet(self):
        """The kernel's DRM (12 00 30) after Mallet's status request, then Mallet's start-up: Mallet's mode wins."""
        run_all(self.m, [KERNEL_DETECT, KERNEL_LED1, h("1110"), h("1500"), h("120030")] + mallet_startup(*WII3))
        self.assertEqual((self.m.mode, self.m.continuous), (0x33, True))
        # ... but a kernel DRM after Mallet's (the race after a later status report) stops the IR:
        self.m.handle_output(h("1500"))
        self.m.handle_output(h("120633"))
        self.m.handle_output(h("120030"))
        self.assertEqual(self.m.data_report([(1, 1, 4)]), h("300000"))
        self.assertIsNone(self.m.data_report([(1, 1, 4)]))


class Paths(unittest.TestCase):
    BOX = wu.CameraBox(162, 134, 862, 634)

    def test_targets_are_the_kiosks(self):
        t = wu.calibration_targets()
        self.assertEqual(len(t), 9)
        self.assertEqual(t[0], (0.1, 0.1))
        self.assertEqual(t[1], (0.5, 0.1))
        self.assertEqual(t[8], (0.9, 0.9))

    def calibration(self, **kw):
        return wu.builtin_path(self.BOX, True, 0, **kw)

    def test_each_target_is_held_long_enough_after_leaving_the_last(self):
        """The kiosk's rules (core/calibration_session.hpp): the dot leaves the last point by more
        than 30 px, then 0.5 s settle, then 1.2 s within 8 px (std-dev <= 2.5 px) with >= 10 samples."""
        path = self.calibration()
        rate = 100.0
        targets = [self.BOX(u, v) for u, v in wu.calibration_targets()]
        rest = path.position(0)[:2]
        t = 0.0
        for k, target in enumerate(targets):
            # first sample farther than 30 px from where the dot rested
            while math.dist(path.position(t)[:2], rest) <= 30:
                t += 1 / rate
            settle_end = t + 0.5
            # the dwell window starts when the dot is within 8 px of the target and stays
            t = settle_end
            while math.dist(path.position(t)[:2], target) > 2:
                t += 1 / rate
            start = t
            while math.dist(path.position(t)[:2], target) <= 2 and t <= path.duration:
                t += 1 / rate
            self.assertGreaterEqual(t - start, 1.2 + 0.5, "target %d held %.2f s" % (k + 1, t - start))
            rest = target

    def test_speeds_stay_plausible_for_the_ir_tracker(self):
        path = wu.builtin_path(self.BOX, True, 6)
        prev = path.position(0)
        for i in range(1, int(path.duration * 100) + 2):
            p = path.position(i / 100)
            self.assertLess(math.dist(p[:2], prev[:2]), 10000 / 100 + 8)   # IrTracker's bound per report
            prev = p

    def test_strokes_cross_the_bars_downwards(self):
        path = wu.builtin_path(self.BOX, False, 4)
        top_y, bottom_y = self.BOX(0, 0.35)[1], self.BOX(0, 0.75)[1]
        bar_y = self.BOX(0, 0.594)[1]   # the bars' tops on a 16:9 screen (percussion scene)
        crossings, prev = [], path.position(0)
        for i in range(1, int(path.duration * 100) + 2):
            p = path.position(i / 100)
            if prev[1] < bar_y <= p[1]:
                crossings.append(p[0])
            prev = p
        self.assertEqual(len(crossings), 4)
        self.assertEqual([round(x) for x in crossings], [351, 694, 351, 694])
        self.assertEqual(path.position(0)[1], top_y)
        self.assertLess(top_y, bar_y)
        self.assertGreater(bottom_y, bar_y)

    def test_loop_repeats_the_strokes(self):
        path = wu.builtin_path(self.BOX, True, 2, loop_strokes=True)
        self.assertEqual(path.position(path.duration + 0.5), path.position(path.loop_from + 0.5))

    def test_script(self):
        path = wu.parse_script("# a\n0 100 100\n1 200 100 6\n2 none\n3 300 300\n", "s")
        self.assertEqual(path.position(0.5), (150.0, 100.0, 4))
        self.assertEqual(path.position(1.5), (200, 100, 6))
        self.assertIsNone(path.position(2.5))
        self.assertEqual(path.position(9), (300, 300, 4))
        for bad, why in (("0 1 2\nx 1 2\n", "s:2: time"), ("1 1 2\n0 1 2\n", "before"),
                         ("0 2000 2\n", "off the camera"), ("0 1\n", "expected"), ("", "no points"),
                         ("0 1 2 99\n", "size")):
            with self.assertRaises(wu.PathError) as e:
                wu.parse_script(bad, "s")
            self.assertIn(why, str(e.exception))

    def test_dump_reads_back(self):
        path = wu.builtin_path(self.BOX, True, 2)
        again = wu.parse_script(path.script_text(), "dump")
        for t in (0, 3.3, 17.01, path.duration - 0.01):
            self.assertEqual([round(v, 3) for v in again.position(t)], [round(v, 3) for v in path.position(t)])

    def test_command_line(self):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            self.assertEqual(wu.main(["--calibration", "--strokes", "1", "--dump-path"]), 0)
        self.assertEqual(wu.parse_script(out.getvalue(), "dump").position(0)[:2], (512.0, 384.0))
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            self.assertEqual(wu.main(["--print-descriptor"]), 0)
        self.assertEqual(bytes.fromhex(out.getvalue()), wu.report_descriptor())
        with tempfile.NamedTemporaryFile("w", suffix=".path", delete=False) as f:
            f.write("0 10 10\n1 20 10\n")
        try:
            o, path = wu.parse_options(["--script", f.name, "--loop"])
            self.assertEqual(path.position(1.5), (15.0, 10.0, 4))
            self.assertEqual(o.go_after_startups, 1)
        finally:
            os.unlink(f.name)
        with contextlib.redirect_stderr(io.StringIO()):
            for bad in ([], ["--script", "/nonexistent"], ["--calibration", "--grid", "3"],
                        ["--strokes", "1", "--bars", "2"], ["--script", "x", "--strokes", "1"]):
                with self.assertRaises(SystemExit) as e:
                    wu.parse_options(bad)
                self.assertEqual(e.exception.code, 2, bad)

    def test_options(self):
        o, path = wu.parse_options(["--calibration", "--strokes", "3"])
        self.assertEqual((o.go_after_switches, o.go_after_startups), (2, None))
        o, _ = wu.parse_options(["--calibration", "--needs-sensitivity", "wii2"])
        self.assertEqual(o.go_after_switches, 3)
        o, _ = wu.parse_options(["--strokes", "3"])
        self.assertEqual((o.go_after_switches, o.go_after_startups), (None, 1))


class FakeKernel:
    """Plays the kernel's side of /dev/uhid over SOCK_SEQPACKET socketpairs (one per switch-on)."""

    def __init__(self):
        self.ends = []
        self.lock = threading.Lock()

    def open(self):
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        with self.lock:
            self.ends.append(ours)
        return theirs.detach()

    def close(self):
        with self.lock:
            for s in self.ends:
                s.close()

    def end(self, i):
        with self.lock:
            return self.ends[i]

    def send(self, i, event):
        self.end(i).send(event)

    def events(self, i, seconds):
        out, end = [], time.monotonic() + seconds
        s = self.end(i)
        while time.monotonic() < end:
            s.settimeout(max(0.001, end - time.monotonic()))
            try:
                buf = s.recv(wu.EVENT_SIZE)
            except (socket.timeout, BlockingIOError):
                break
            if not buf:
                break
            out.append(wu.unpack_event(buf))
        return out


class EmulatorLoop(unittest.TestCase):
    def test_a_session_on_a_fake_uhid(self):
        kernel = FakeKernel()
        o, path = wu.parse_options(["--strokes", "2", "--stats-every", "0", "--lead-in", "0.2"])
        lines = []
        model = wu.WiimoteModel(log=lines.append)
        emu = wu.Emulator(o, model, path, open_uhid=kernel.open, log=lines.append)
        thread = threading.Thread(target=emu.run, kwargs={"until": time.monotonic() + 3.0})
        thread.start()
        try:
            while not kernel.ends:
                time.sleep(0.01)
            (create,) = kernel.events(0, 0.2)
            self.assertEqual(create[0], wu.UHID_CREATE2)
            self.assertEqual((create[1]["bus"], create[1]["vendor"], create[1]["product"], create[1]["name"]),
                             (5, 0x057E, 0x0306, "Nintendo RVL-CNT-01"))
            kernel.send(0, bytes.fromhex("02000000") + bytes(8))                       # START
            kernel.send(0, bytes.fromhex("04000000"))                                  # OPEN
            for r in MALLET_CONNECT:
                kernel.send(0, wu.pack_output_event(r))
            kernel.send(0, bytes.fromhex("09000000" "05000000" "20" "02"))            # GET_REPORT
            got = kernel.events(0, 1.0)
            inputs = [ev["data"] for t, ev in got if t == wu.UHID_INPUT2]
            replies = [ev for t, ev in got if t == wu.UHID_GET_REPORT_REPLY]
            self.assertIn(h("20000010" "0000c8"), inputs)
            self.assertIn(h("2200001200"), inputs)
            ir = [r for r in inputs if r[0] == 0x33]
            self.assertGreater(len(ir), 10)   # about 100 a second once 0x12 came (fewer on a loaded host)
            x, y, _ = decode_ir(ir[-1])[0]
            self.assertLessEqual(max(abs(x - 351), abs(y - 309)), 1)   # the strokes' first point, +-1 px jitter
            self.assertTrue(any("go (IR start-up #1 seen)" in line for line in lines))
            emu.want["off"] = True
            got = kernel.events(0, 0.5)
            self.assertIn(wu.UHID_DESTROY, [t for t, _ in got])
            emu.want["on"] = True
            while len(kernel.ends) < 2:
                time.sleep(0.01)
            (again,) = kernel.events(1, 0.2)
            self.assertEqual(again[0], wu.UHID_CREATE2)
        finally:
            emu.want["stop"] = True
            thread.join(5)
            kernel.close()
        self.assertFalse(thread.is_alive())
        self.assertEqual([(r["id"], r["err"]) for r in replies], [(5, 5)])   # EIO: the remote has no such report
        self.assertTrue(any("GET_REPORT" in line for line in lines))

    def test_get_report_is_answered(self):
        kernel = FakeKernel()
        o, path = wu.parse_options(["--strokes", "1", "--stats-every", "0"])
        emu = wu.Emulator(o, wu.WiimoteModel(), path, open_uhid=kernel.open)
        emu.t0 = time.monotonic()
        emu.create()
        kernel.events(0, 0.1)
        emu.handle_event(bytes.fromhex("09000000" "05000000" "20" "02"), 0.0)
        emu.handle_event(bytes.fromhex("0d000000" "06000000" "12" "01" "0300") + h("120633"), 0.0)
        got = kernel.events(0, 0.2)
        self.assertEqual(got[0][0], wu.UHID_GET_REPORT_REPLY)
        raw = wu.pack_get_report_reply(5, 5)
        self.assertEqual(got[0], wu.unpack_event(raw))
        self.assertEqual(got[1], (wu.UHID_SET_REPORT_REPLY, {"id": 6, "err": 0}))
        answers = [ev["data"] for t, ev in got if t == wu.UHID_INPUT2]
        self.assertEqual(answers, [h("2200001200")])   # the output report it carried was answered
        emu.destroy("test")
        kernel.close()


@unittest.skipUnless(MALLET, "no built mallet (set MALLET=path or build one under build/)")
class MalletCrossCheck(unittest.TestCase):
    """Mallet's own parser and calibration fit on what the emulator produces."""

    def decode(self, reports):
        text = "\n".join(wu.hexs(r) for r in reports) + "\n"
        p = subprocess.run([MALLET, "wiimote", "decode", "--hex", "-"], input=text, capture_output=True, text=True,
                           timeout=60)
        self.assertEqual(p.returncode, 0, p.stderr)
        return p.stdout.splitlines()

    def test_every_report_parses_and_the_dots_match(self):
        m = wu.WiimoteModel()
        answers = run_all(m, [KERNEL_DETECT, KERNEL_LED1] + KERNEL_POLL + MALLET_CONNECT)
        dots = [(0, 0, 1), (1023, 767, 15), (512, 384, 4), (300, 700, 8), (255, 256, 2), (768, 511, 9)]
        data = [m.data_report([d, None, (d[1], d[0] % 768, 3)]) for d in dots]
        lines = self.decode(answers + data)   # status, acks and read data print nothing but must parse
        self.assertEqual(len(lines), len(dots))
        for d, line in zip(dots, lines):
            self.assertEqual(line, "%d,%d,%d - %d,%d,3 -" % (d[0], d[1], d[2], d[1], d[0] % 768))
        basic = wu.WiimoteModel()
        run_all(basic, KERNEL_IR_OPEN)
        b = [basic.data_report([d, (d[1], d[0] % 768, 0)]) for d in dots]
        lines = self.decode(b)
        for d, line in zip(dots, lines):
            self.assertEqual(line, "%d,%d,? %d,%d,? - -" % (d[0], d[1], d[1], d[0] % 768))
        basic.handle_output(h("120437"))
        (line,) = self.decode([basic.data_report([(9, 10, 0)])])
        self.assertEqual(line, "9,10,? - - -")

    def test_calibration_points_fit(self):
        box = wu.CameraBox(162, 134, 862, 634)
        with tempfile.TemporaryDirectory() as d:
            points = os.path.join(d, "points.csv")
            with open(points, "w") as f:
                f.write("cam_x,cam_y,screen_x,screen_y\n")
                for u, v in wu.calibration_targets():
                    x, y = box(u, v)
                    f.write("%d,%d,%g,%g\n" % (round(x), round(y), u, v))
            out = os.path.join(d, "calibration.toml")
            p = subprocess.run([MALLET, "calibrate", "fit", "--points", points, "--out", out],
                               capture_output=True, text=True, timeout=60)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            p = subprocess.run([MALLET, "calibrate", "map", "--calibration", out, "351", "309"],
                               capture_output=True, text=True, timeout=60)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertIn("0.27", p.stdout)

    def test_a_recording_plays_back_in_mallet(self):
        """--record writes Mallet's replay format; `mallet wiimote monitor --replay` runs it."""
        m = wu.WiimoteModel()
        run_all(m, MALLET_CONNECT)
        with tempfile.TemporaryDirectory() as d:
            rec = os.path.join(d, "emulated.replay")
            with open(rec, "w") as f:
                f.write("# mallet-wiimote-replay 1\n")
                for i in range(200):
                    f.write("%d %s\n" % (i * 10_000_000, wu.hexs(m.data_report([(400 + i, 300, 4)]))))
            p = subprocess.run([MALLET, "wiimote", "monitor", "--replay", rec, "--seconds", "1.5"],
                               capture_output=True, text=True, timeout=60)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            self.assertRegex(p.stdout + p.stderr, r"\d")


if __name__ == "__main__":
    unittest.main()
