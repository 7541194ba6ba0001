#!/usr/bin/env python3
"""A Wii Remote (RVL-CNT-01) emulated at the kernel through /dev/uhid, for the VM system test.

What it is
    A small stand-in for a paired Wii Remote that runs INSIDE the Debian 12 guest (python3,
    standard library only, as root). It creates a HID device with UHID_CREATE2 on the
    Bluetooth bus, vendor 0x057E, product 0x0306, name "Nintendo RVL-CNT-01" and the remote's
    report descriptor (output reports 0x10..0x1A, input reports 0x20..0x22, 0x30..0x37,
    0x3D..0x3F). The guest kernel's hid-wiimote driver binds it exactly as it binds a paired
    remote (its evdev nodes "Nintendo Wii Remote", "... Accelerometer", "... IR" appear, and
    /dev/hidraw* through udev with the package's rule), and Mallet's hidapi transport talks
    to it through that hidraw node, next to the kernel driver.

    It answers the output reports the kernel driver and Mallet send like a remote does:
    0x15 status request -> 0x20 status; 0x17 read -> 0x21 data (or an error code: no
    extension, no Motion Plus); 0x16 write -> 0x22 ack; 0x12 reporting mode (remembered; acked
    when bit 0x02 asks); 0x13/0x1A IR camera enable; 0x11 LEDs; rumble in every report. It
    streams data reports at 100 Hz in the current reporting mode (0x33 extended IR for Mallet,
    0x36/0x37 basic IR when the kernel's IR node is opened, ...) with one IR dot moved along a
    scripted path. See WIIMOTE.md beside this file for what the kernel and Mallet each send.

How the VM test uses it
    The harness copies this folder into the image (/opt/mallet-test/) and runs, e.g.
        systemd-run --unit wiimote-emulator python3 /opt/mallet-test/wiimote_uhid.py \
            --calibration --strokes 40
    then waits for the kiosk's "Wii Remote ... connected", the calibration and strikes in the
    journal. `systemctl kill -s USR1 wiimote-emulator` switches the remote off (UHID_DESTROY),
    `-s USR2` switches it on again (a fresh UHID_CREATE2), so the test can check that Mallet
    reconnects. `-s HUP` starts the built-in path now (skips the wait for the kiosk's IR
    start-ups). Everything received and sent is logged on stderr (the unit's journal:
    `journalctl -u wiimote-emulator`), so a failing run can be read from the guest's journal.

The path (what the camera sees)
    --script FILE   lines "SECONDS X Y [SIZE]" or "SECONDS none": camera pixels 0..1023 x
                    0..767 at that time (seconds from "go"), linear between two dots, no dot
                    from a "none" line to the next line; '#' starts a comment.
    --calibration   the kiosk's calibration screen: rest at the centre until the kiosk has
                    chosen the IR sensitivity (its 3rd IR start-up: connect, the tuner's first
                    preset, the preset chosen), then the 3x3 targets in reading order, each
                    reached in --travel s and held --dwell s (the screen needs 0.5 s settle +
                    1.2 s still), mapped to the camera through --camera-box.
    --strokes N     after the calibration (or alone): N downswings through the bars at the
                    normalised screen x positions --bars, from --stroke-top to --stroke-bottom.
    Before "go" the dot rests at the path's start; after the end it stays at the last point.

Layout of struct uhid_event (include/uapi/linux/uhid.h, Linux 6.1; packed, host byte order)
    __u32 type, then a union (the largest member, create2, makes the event 4376 bytes):
      UHID_DESTROY=1  (no payload)
      UHID_START=2    __u64 dev_flags
      UHID_STOP=3, UHID_OPEN=4, UHID_CLOSE=5 (no payload)
      UHID_OUTPUT=6   __u8 data[4096]; __u16 size; __u8 rtype (0 feature, 1 output, 2 input)
      UHID_GET_REPORT=9        __u32 id; __u8 rnum; __u8 rtype
      UHID_GET_REPORT_REPLY=10 __u32 id; __u16 err; __u16 size; __u8 data[4096]
      UHID_CREATE2=11 __u8 name[128]; __u8 phys[64]; __u8 uniq[64]; __u16 rd_size; __u16 bus;
                      __u32 vendor; __u32 product; __u32 version; __u32 country;
                      __u8 rd_data[4096]
      UHID_INPUT2=12  __u16 size; __u8 data[4096]
      UHID_SET_REPORT=13       __u32 id; __u8 rnum; __u8 rtype; __u16 size; __u8 data[4096]
      UHID_SET_REPORT_REPLY=14 __u32 id; __u16 err
    The kernel zero-fills short writes (at least the 4-byte type); reads return one event.

The protocol logic (WiimoteModel, the path) is pure and tested on the host without /dev/uhid:
    python3 -m unittest packaging/tests/system/guest/test_wiimote_uhid.py
"""

import argparse
import errno
import os
import random
import select
import signal
import struct
import sys
import time

# ---------------------------------------------------------------------------------------
# uhid ABI (include/uapi/linux/uhid.h)

UHID_DESTROY = 1
UHID_START = 2
UHID_STOP = 3
UHID_OPEN = 4
UHID_CLOSE = 5
UHID_OUTPUT = 6
UHID_GET_REPORT = 9
UHID_GET_REPORT_REPLY = 10
UHID_CREATE2 = 11
UHID_INPUT2 = 12
UHID_SET_REPORT = 13
UHID_SET_REPORT_REPLY = 14

UHID_FEATURE_REPORT = 0
UHID_OUTPUT_REPORT = 1
UHID_INPUT_REPORT = 2

UHID_DATA_MAX = 4096
HID_MAX_DESCRIPTOR_SIZE = 4096
BUS_BLUETOOTH = 0x05

EVENT_NAMES = {
    UHID_DESTROY: "DESTROY", UHID_START: "START", UHID_STOP: "STOP", UHID_OPEN: "OPEN",
    UHID_CLOSE: "CLOSE", UHID_OUTPUT: "OUTPUT", UHID_GET_REPORT: "GET_REPORT",
    UHID_GET_REPORT_REPLY: "GET_REPORT_REPLY", UHID_CREATE2: "CREATE2", UHID_INPUT2: "INPUT2",
    UHID_SET_REPORT: "SET_REPORT", UHID_SET_REPORT_REPLY: "SET_REPORT_REPLY",
}

# '<' everywhere: packed, and the guest (x86-64) is little-endian like the kernel's host order.
_CREATE2 = struct.Struct("<I128s64s64sHHIIII%ds" % HID_MAX_DESCRIPTOR_SIZE)
_INPUT2_HEAD = struct.Struct("<IH")
_OUTPUT_TAIL = struct.Struct("<HB")            # after data[4096]
_GET_REPORT = struct.Struct("<IIBB")           # type, id, rnum, rtype
_GET_REPORT_REPLY_HEAD = struct.Struct("<IIHH")  # type, id, err, size (then data)
_SET_REPORT_HEAD = struct.Struct("<IIBBH")     # type, id, rnum, rtype, size (then data)
_SET_REPORT_REPLY = struct.Struct("<IIH")      # type, id, err
EVENT_SIZE = _CREATE2.size                     # 4 + 4372 = 4376, sizeof(struct uhid_event)
OUTPUT_DATA_OFFSET = 4
OUTPUT_SIZE_OFFSET = 4 + UHID_DATA_MAX          # 4100: __u16 size, then __u8 rtype at 4102


def _pad(event):
    """An event padded with zeros to sizeof(struct uhid_event), as the kernel reads it."""
    return event + bytes(EVENT_SIZE - len(event))


def pack_create2(name, phys, uniq, descriptor, bus=BUS_BLUETOOTH, vendor=0x057E, product=0x0306,
                 version=0, country=0):
    if not 0 < len(descriptor) <= HID_MAX_DESCRIPTOR_SIZE:
        raise ValueError("report descriptor must be 1..%d bytes" % HID_MAX_DESCRIPTOR_SIZE)
    return _CREATE2.pack(UHID_CREATE2, name.encode()[:127], phys.encode()[:63], uniq.encode()[:63],
                         len(descriptor), bus, vendor, product, version, country, bytes(descriptor))


def pack_input2(report):
    if len(report) > UHID_DATA_MAX:
        raise ValueError("input report longer than %d bytes" % UHID_DATA_MAX)
    return _pad(_INPUT2_HEAD.pack(UHID_INPUT2, len(report)) + bytes(report))


def pack_destroy():
    return _pad(struct.pack("<I", UHID_DESTROY))


def pack_get_report_reply(request_id, err, data=b""):
    return _pad(_GET_REPORT_REPLY_HEAD.pack(UHID_GET_REPORT_REPLY, request_id, err, len(data)) + bytes(data))


def pack_set_report_reply(request_id, err):
    return _pad(_SET_REPORT_REPLY.pack(UHID_SET_REPORT_REPLY, request_id, err))


def pack_output_event(report, rtype=UHID_OUTPUT_REPORT):
    """What the kernel writes for an output report (used by the tests, which play the kernel)."""
    head = struct.pack("<I", UHID_OUTPUT) + bytes(report) + bytes(UHID_DATA_MAX - len(report))
    return _pad(head + _OUTPUT_TAIL.pack(len(report), rtype))


def unpack_event(buf):
    """(type, fields) of an event read from /dev/uhid; short reads are zero-extended."""
    if len(buf) < 4:
        raise ValueError("uhid event shorter than its 4-byte type")
    buf = bytes(buf) + bytes(max(0, EVENT_SIZE - len(buf)))
    (etype,) = struct.unpack_from("<I", buf, 0)
    if etype == UHID_OUTPUT:
        size, rtype = _OUTPUT_TAIL.unpack_from(buf, OUTPUT_SIZE_OFFSET)
        size = min(size, UHID_DATA_MAX)
        return etype, {"data": buf[OUTPUT_DATA_OFFSET:OUTPUT_DATA_OFFSET + size], "rtype": rtype}
    if etype == UHID_START:
        (flags,) = struct.unpack_from("<Q", buf, 4)
        return etype, {"dev_flags": flags}
    if etype == UHID_GET_REPORT:
        _, rid, rnum, rtype = _GET_REPORT.unpack_from(buf, 0)
        return etype, {"id": rid, "rnum": rnum, "rtype": rtype}
    if etype == UHID_SET_REPORT:
        _, rid, rnum, rtype, size = _SET_REPORT_HEAD.unpack_from(buf, 0)
        size = min(size, UHID_DATA_MAX)
        off = _SET_REPORT_HEAD.size
        return etype, {"id": rid, "rnum": rnum, "rtype": rtype, "data": buf[off:off + size]}
    if etype == UHID_CREATE2:
        f = _CREATE2.unpack_from(buf, 0)
        return etype, {"name": f[1].rstrip(b"\0").decode(errors="replace"),
                       "phys": f[2].rstrip(b"\0").decode(errors="replace"),
                       "uniq": f[3].rstrip(b"\0").decode(errors="replace"),
                       "bus": f[5], "vendor": f[6], "product": f[7], "version": f[8],
                       "country": f[9], "descriptor": f[10][:f[4]]}
    if etype == UHID_INPUT2:
        _, size = _INPUT2_HEAD.unpack_from(buf, 0)
        return etype, {"data": buf[_INPUT2_HEAD.size:_INPUT2_HEAD.size + min(size, UHID_DATA_MAX)]}
    if etype == UHID_GET_REPORT_REPLY:
        _, rid, err, size = _GET_REPORT_REPLY_HEAD.unpack_from(buf, 0)
        off = _GET_REPORT_REPLY_HEAD.size
        return etype, {"id": rid, "err": err, "data": buf[off:off + min(size, UHID_DATA_MAX)]}
    if etype == UHID_SET_REPORT_REPLY:
        _, rid, err = _SET_REPORT_REPLY.unpack_from(buf, 0)
        return etype, {"id": rid, "err": err}
    return etype, {}


# ---------------------------------------------------------------------------------------
# The remote's HID report descriptor, written from the protocol's report lengths: every
# report is a run of bytes (vendor page), its length the payload after the id byte.

OUTPUT_PAYLOAD = {0x10: 1, 0x11: 1, 0x12: 2, 0x13: 1, 0x14: 1, 0x15: 1, 0x16: 21, 0x17: 6,
                  0x18: 21, 0x19: 1, 0x1A: 1}
INPUT_PAYLOAD = {0x20: 6, 0x21: 21, 0x22: 4, 0x30: 2, 0x31: 5, 0x32: 10, 0x33: 17, 0x34: 21,
                 0x35: 21, 0x36: 21, 0x37: 21, 0x3D: 21, 0x3E: 21, 0x3F: 21}
DATA_MODES = (0x30, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37, 0x3D, 0x3E, 0x3F)


def report_descriptor():
    d = bytearray()
    d += b"\x05\x01"          # Usage Page (Generic Desktop)
    d += b"\x09\x05"          # Usage (Game Pad)
    d += b"\xa1\x01"          # Collection (Application)
    d += b"\x06\x00\xff"      #   Usage Page (vendor 0xFF00): the bytes mean nothing to hid-input
    d += b"\x15\x00"          #   Logical Minimum (0)
    d += b"\x26\xff\x00"      #   Logical Maximum (255)
    d += b"\x75\x08"          #   Report Size (8)
    for rid, n in sorted(OUTPUT_PAYLOAD.items()):
        d += bytes((0x85, rid, 0x95, n, 0x09, 0x01, 0x91, 0x00))  # Report ID, Count, Usage, Output
    for rid, n in sorted(INPUT_PAYLOAD.items()):
        d += bytes((0x85, rid, 0x95, n, 0x09, 0x01, 0x81, 0x00))  # Report ID, Count, Usage, Input
    d += b"\xc0"              # End Collection
    return bytes(d)


# ---------------------------------------------------------------------------------------
# The remote

# The published sensitivity blocks (wiibrew "IR Camera"), least sensitive first: only to name
# what is written in the log, and for --needs-sensitivity.
SENSITIVITY_BLOCK1 = [
    ("wii1", bytes((0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0x64, 0x00, 0xFE))),
    ("wii2", bytes((0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0x96, 0x00, 0xB4))),
    ("wii3", bytes((0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0xAA, 0x00, 0x64))),
    ("wii4", bytes((0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0xC8, 0x00, 0x36))),
    ("wii5", bytes((0x07, 0x00, 0x00, 0x71, 0x01, 0x00, 0x72, 0x00, 0x20))),
    ("marcan", bytes((0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x90, 0x00, 0xC0))),
    ("max", bytes((0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x90, 0x00, 0x41))),
]
SENSITIVITY_NAMES = [n for n, _ in SENSITIVITY_BLOCK1]

CAMERA_BASE = 0xB00000
CAMERA_SIZE = 0x100
SPEAKER_BASE = 0xA20000
SPEAKER_SIZE = 0x10
EXTENSION_BASE = 0xA40000      # nothing plugged in
MOTION_PLUS_BASE = 0xA60000    # no Motion Plus
EEPROM_SIZE = 0x1700

ERR_OK = 0
ERR_BAD = 3                    # "error" in an ack (an unusable request)
ERR_NO_DEVICE = 7              # read/write of a device that is not there (no extension, no MP)
ERR_NO_MEMORY = 8              # no such memory

ACCEL_AT_REST = bytes((0x80, 0x80, 0x9A))   # lying flat: about +1 g on z


def hexs(data):
    return " ".join("%02x" % b for b in data)


def encode_extended_ir(dots):
    """12 bytes: four slots of [X lo, Y lo, Y9 Y8 X9 X8 S3 S2 S1 S0]; empty = ff ff ff."""
    out = bytearray()
    for i in range(4):
        dot = dots[i] if i < len(dots) else None
        if dot is None:
            out += b"\xff\xff\xff"
            continue
        x, y, size = dot
        out += bytes((x & 0xFF, y & 0xFF, ((y >> 8) & 3) << 6 | ((x >> 8) & 3) << 4 | (size & 0x0F)))
    return bytes(out)


def encode_basic_ir(dots):
    """10 bytes: two pairs of [X1 lo, Y1 lo, Y1hi X1hi Y2hi X2hi, X2 lo, Y2 lo]; empty = 0x3ff."""
    out = bytearray()
    for p in range(2):
        pair = []
        for i in (2 * p, 2 * p + 1):
            dot = dots[i] if i < len(dots) else None
            pair.append((0x3FF, 0x3FF) if dot is None else (dot[0], dot[1]))
        (x1, y1), (x2, y2) = pair
        out += bytes((x1 & 0xFF, y1 & 0xFF,
                      ((y1 >> 8) & 3) << 6 | ((x1 >> 8) & 3) << 4 | ((y2 >> 8) & 3) << 2 | ((x2 >> 8) & 3),
                      x2 & 0xFF, y2 & 0xFF))
    return bytes(out)


class WiimoteModel:
    """The remote's side of the protocol as pure bytes: output report in, input reports out.

    handle_output(report) -> [input report, ...]   (answers: status, read data, acks)
    data_report(dots)     -> bytes or None          (the current mode's data report, or
                                                     nothing: reporting stopped, or not
                                                     continuous and nothing changed)
    ir_report(x, y)       -> bytes                  (one dot, current mode; 0x33 if the mode
                                                     carries no IR)
    Byte 0 of every report is its id, exactly as hidraw passes it.
    """

    def __init__(self, battery=0xC8, battery_low=False, dot_size=4, status_resets="unsolicited",
                 needs_sensitivity=None, log=None, absent_error=None):
        if status_resets not in ("unsolicited", "all", "none"):
            raise ValueError("status_resets must be unsolicited, all or none")
        self.battery = battery & 0xFF
        self.battery_low = battery_low
        self.dot_size = dot_size
        self.status_resets = status_resets
        self.needs_index = SENSITIVITY_NAMES.index(needs_sensitivity) if needs_sensitivity else 0
        # What a read or write of the absent extension / Motion Plus gets: 7, as a real remote
        # (a write or read on the I2C bus that no device acknowledges; Dolphin does the same).
        self.absent_error = ERR_NO_DEVICE if absent_error is None else absent_error
        self.log = log or (lambda _msg: None)
        self._poll_seen = {}        # output report -> times seen (log thinning)
        self.startups = 0           # IR start-ups completed with a continuous 0x12 (Mallet's)
        self.switches = 0           # ... of them, those not right after a connect (sensitivity switches)
        self.reset()

    # --- state

    def reset(self):
        """A remote just switched on: blinking LEDs, buttons-only reports, camera off."""
        self.leds = 0
        self.rumble = False
        self.mode = 0x30
        self.continuous = False
        self.reporting = True
        self.pixel_clock = False
        self.ir_logic = False
        self.speaker = False
        self.muted = False
        self.camera = bytearray(b"\x00" * CAMERA_SIZE)
        self.speaker_regs = bytearray(SPEAKER_SIZE)
        self.eeprom = bytearray(EEPROM_SIZE)
        self.eeprom[0x16:0x20] = bytes((0x80, 0x80, 0x80, 0x00, 0x9A, 0x9A, 0x9A, 0x00, 0x40, 0x00))
        self.eeprom[0x26:0x30] = self.eeprom[0x16:0x20]
        self._last_data = None
        self._camera_ready_since_mode = False
        self._status_since_startup = False
        self._full_half = 0
        self._warned = set()

    @property
    def camera_sending(self):
        return self.pixel_clock and self.ir_logic and self.camera[0x30] == 0x08

    @property
    def camera_format(self):
        return self.camera[0x33]   # 1 basic, 3 extended, 5 full

    def sensitivity_name(self):
        block = bytes(self.camera[0x00:0x09])
        for name, b1 in SENSITIVITY_BLOCK1:
            if b1 == block:
                return name
        return "custom " + hexs(block)

    def sees_dot(self):
        """The camera sees the LED with its current sensitivity (see --needs-sensitivity)."""
        if not self.needs_index:
            return True
        block = bytes(self.camera[0x00:0x09])
        for i, (_, b1) in enumerate(SENSITIVITY_BLOCK1):
            if b1 == block:
                return i >= self.needs_index
        return True

    # --- input reports

    def buttons(self):
        return b"\x00\x00"

    def status_report(self):
        flags = (0x01 if self.battery_low else 0) | (0x04 if self.speaker else 0) | \
                (0x08 if self.pixel_clock and self.ir_logic else 0) | (self.leds & 0x0F) << 4
        return bytes((0x20,)) + self.buttons() + bytes((flags, 0, 0, self.battery))

    def _after_status(self, solicited):
        if self.status_resets == "all" or (self.status_resets == "unsolicited" and not solicited):
            if self.reporting:
                self.log("status report: data reports stop until the reporting mode is set again")
            self.reporting = False

    def unsolicited_status(self):
        """A status report the remote sends by itself (e.g. an extension event)."""
        report = self.status_report()
        self._after_status(solicited=False)
        return report

    def ack(self, report_id, error=ERR_OK):
        return bytes((0x22,)) + self.buttons() + bytes((report_id, error))

    def _read_data(self, address, size, error=ERR_OK, data=b""):
        """0x21 reports answering a read: 16-byte chunks, or one report with the error code."""
        if error:
            return [bytes((0x21,)) + self.buttons() + bytes((error, (address >> 8) & 0xFF, address & 0xFF))
                    + bytes(16)]
        out = []
        for off in range(0, size, 16):
            chunk = data[off:off + 16]
            a = address + off
            out.append(bytes((0x21,)) + self.buttons() + bytes((((len(chunk) - 1) << 4), (a >> 8) & 0xFF, a & 0xFF))
                       + chunk + bytes(16 - len(chunk)))
        return out

    def ir_bytes(self, field, dots):
        """The IR field of a data report: `field` is 'extended' (12), 'basic' (10) or 'full'."""
        empty = {"extended": b"\xff" * 12, "basic": b"\xff" * 10}
        if not self.camera_sending or not self.sees_dot():
            dots = []
        expected = {"extended": 3, "basic": 1}.get(field)
        if expected is not None and self.camera_format != expected:
            if dots and ("format", field, self.camera_format) not in self._warned:
                self._warned.add(("format", field, self.camera_format))
                self.log("warning: data report 0x%02x carries %s IR but the camera is in format %d "
                         "(register 0xb00033): sending no dots" % (self.mode, field, self.camera_format))
            return empty[field]
        if field == "extended":
            return encode_extended_ir(dots)
        return encode_basic_ir(dots)

    def data_report(self, dots):
        """The data report of the current mode for this tick, or None (see the class doc).

        `dots`: up to four (x, y, size) camera dots or None for empty slots.
        """
        if not self.reporting:
            return None
        m, b = self.mode, self.buttons()
        ext = lambda n: bytes(n)  # no extension: zeros
        if m == 0x30:
            r = bytes((m,)) + b
        elif m == 0x31:
            r = bytes((m,)) + b + ACCEL_AT_REST
        elif m == 0x32:
            r = bytes((m,)) + b + ext(8)
        elif m == 0x33:
            r = bytes((m,)) + b + ACCEL_AT_REST + self.ir_bytes("extended", dots)
        elif m == 0x34:
            r = bytes((m,)) + b + ext(19)
        elif m == 0x35:
            r = bytes((m,)) + b + ACCEL_AT_REST + ext(16)
        elif m == 0x36:
            r = bytes((m,)) + b + self.ir_bytes("basic", dots) + ext(9)
        elif m == 0x37:
            r = bytes((m,)) + b + ACCEL_AT_REST + self.ir_bytes("basic", dots) + ext(6)
        elif m == 0x3D:
            r = bytes((m,)) + ext(21)
        else:  # 0x3e / 0x3f: full IR, interleaved; not emulated beyond its shape (no dots)
            if ("full",) not in self._warned:
                self._warned.add(("full",))
                self.log("warning: full IR mode (0x3e/0x3f) is not emulated: its reports carry no dots")
            rid = 0x3E + self._full_half
            self._full_half ^= 1
            r = bytes((rid,)) + b + bytes((0x80,)) + b"\xff" * 18
        if not self.continuous:
            if r == self._last_data:
                return None
        self._last_data = r
        return r

    def ir_report(self, x, y, size=None):
        """One dot at camera pixel (x, y) in the current mode's report (0x33 if it has no IR),
        whatever the reporting state: what the camera would send now."""
        saved = (self.mode, self.reporting, self.continuous, self._last_data)
        if self.mode not in (0x33, 0x36, 0x37):
            self.mode = 0x33
        self.reporting, self.continuous = True, True
        try:
            return self.data_report([(x, y, self.dot_size if size is None else size)])
        finally:
            self.mode, self.reporting, self.continuous, self._last_data = saved

    # --- output reports

    def handle_output(self, report):
        """One output report (byte 0 = id) -> the input reports that answer it, in order."""
        report = bytes(report)
        if not report:
            self.log("<- empty output report: ignored")
            return []
        rid = report[0]
        need = OUTPUT_PAYLOAD.get(rid)
        if need is None:
            self.log("<- %s: unknown output report 0x%02x, ignored" % (hexs(report), rid))
            return []
        if len(report) < 2:
            self.log("<- %s: too short for 0x%02x, ignored" % (hexs(report), rid))
            return []
        flags = report[1]
        rumble = bool(flags & 0x01)
        if rumble != self.rumble:
            self.rumble = rumble
        wants_ack = bool(flags & 0x02)
        answers = []
        what = ""
        if rid == 0x10:
            what = "rumble"
        elif rid == 0x11:
            self.leds = flags >> 4
            what = "LEDs %s" % "".join("*" if self.leds & (1 << i) else "." for i in range(4))
        elif rid == 0x12:
            if len(report) < 3:
                self.log("<- %s: reporting mode without its mode byte, ignored" % hexs(report))
                return []
            mode, cont = report[2], bool(flags & 0x04)
            if mode not in DATA_MODES:
                what = "reporting mode 0x%02x: not a data report, refused" % mode
                if wants_ack:
                    answers.append(self.ack(rid, ERR_BAD))
                    wants_ack = False
            else:
                self.mode, self.continuous, self.reporting = mode, cont, True
                self._last_data = None
                what = "reporting mode 0x%02x %s" % (mode, "continuous" if cont else "on change")
                if cont and self._camera_ready_since_mode:
                    self._camera_ready_since_mode = False
                    self.startups += 1
                    if self._status_since_startup:
                        kind = "after a connect (a status request came first)"
                    else:
                        self.switches += 1
                        kind = "sensitivity switch #%d" % self.switches
                    self._status_since_startup = False
                    what += "; IR start-up #%d complete, %s: camera format %d, sensitivity %s" % (
                        self.startups, kind, self.camera_format, self.sensitivity_name())
        elif rid == 0x13:
            self.pixel_clock = bool(flags & 0x04)
            what = "IR pixel clock %s" % ("on" if self.pixel_clock else "off")
        elif rid == 0x14:
            self.speaker = bool(flags & 0x04)
            what = "speaker %s" % ("on" if self.speaker else "off")
        elif rid == 0x15:
            what = "status request"
            self._status_since_startup = True
            answers.append(self.status_report())
            self._after_status(solicited=True)
            wants_ack = False
        elif rid == 0x16:
            what, error = self._write(report)
            answers.append(self.ack(rid, error))
            wants_ack = False
        elif rid == 0x17:
            what, replies = self._read(report)
            answers.extend(replies)
            wants_ack = False
        elif rid == 0x18:
            what = "speaker data"
        elif rid == 0x19:
            self.muted = bool(flags & 0x04)
            what = "speaker %s" % ("muted" if self.muted else "unmuted")
        elif rid == 0x1A:
            self.ir_logic = bool(flags & 0x04)
            what = "IR logic %s" % ("on" if self.ir_logic else "off")
        if wants_ack:
            answers.append(self.ack(rid, ERR_OK))
        notes = (", ack requested" if flags & 0x02 and rid not in (0x15, 0x16, 0x17) else "") + \
                (", rumble on" if rumble else "")
        if rid in (0x16, 0x17) and len(report) > 2 and report[2] in (0xA4, 0xA6):
            # hid-wiimote's extension / Motion Plus poll, every 4 s for as long as it is bound:
            # its first few, then one in 15, so that the log stays readable.
            seen = self._poll_seen[report] = self._poll_seen.get(report, 0) + 1
            if seen > 3 and seen % 15:
                return answers
            if seen > 3:
                notes += " (the kernel's poll, seen %d times; 1 in 15 logged)" % seen
        self.log("<- %s  %s%s" % (hexs(report), what, notes))
        for a in answers:
            self.log("-> %s  %s" % (hexs(a), describe_input(a)))
        return answers

    @staticmethod
    def _address(report):
        return (report[2] << 16) | (report[3] << 8) | report[4]

    def _region(self, registers, address, size):
        """(bytearray, offset) holding [address, address+size), or (None, error code)."""
        if not registers:
            if address + size <= EEPROM_SIZE:
                return self.eeprom, address
            return None, ERR_NO_MEMORY
        if CAMERA_BASE <= address and address + size <= CAMERA_BASE + CAMERA_SIZE:
            return self.camera, address - CAMERA_BASE
        if SPEAKER_BASE <= address and address + size <= SPEAKER_BASE + SPEAKER_SIZE:
            return self.speaker_regs, address - SPEAKER_BASE
        if address & 0xFF0000 in (EXTENSION_BASE, MOTION_PLUS_BASE):
            return None, self.absent_error
        return None, ERR_NO_MEMORY

    def _write(self, report):
        if len(report) < 6:
            return "write: too short (%d bytes)" % len(report), ERR_BAD
        registers = bool(report[1] & 0x04)
        address, size = self._address(report), report[5]
        space = "registers" if registers else "EEPROM"
        if not 1 <= size <= 16 or len(report) < 6 + size:
            return "write of %d bytes at 0x%06x (%s): bad size" % (size, address, space), ERR_BAD
        data = report[6:6 + size]
        mem, where = self._region(registers, address, size)
        text = "write 0x%06x = %s (%s)" % (address, hexs(data), space)
        if mem is None:
            return text + ": %s" % ("no such memory" if where == ERR_NO_MEMORY else "no device there"), where
        mem[where:where + size] = data
        if mem is self.camera:
            text += self._camera_note(address - CAMERA_BASE, data)
        return text, ERR_OK

    def _camera_note(self, offset, data):
        if offset == 0x30:
            if data[0] == 0x08:
                self._camera_ready_since_mode = True
                return ": camera sending"
            return ": camera on, not sending" if data[0] == 0x01 else ""
        if offset == 0x00 and len(data) == 9:
            return ": sensitivity block 1 = %s" % self.sensitivity_name()
        if offset == 0x1A:
            return ": sensitivity block 2"
        if offset == 0x33:
            return ": format %s" % {1: "basic", 3: "extended", 5: "full"}.get(data[0], "0x%02x?" % data[0])
        return ""

    def _read(self, report):
        if len(report) < 7:
            return "read: too short (%d bytes)" % len(report), []
        registers = bool(report[1] & 0x04)
        address, size = self._address(report), (report[5] << 8) | report[6]
        space = "registers" if registers else "EEPROM"
        text = "read %d bytes at 0x%06x (%s)" % (size, address, space)
        if size == 0:
            return text + ": nothing asked", []
        mem, where = self._region(registers, address, size)
        if mem is None:
            text += ": %s (error %d)" % ("no such memory" if where == ERR_NO_MEMORY else "no device there", where)
            if where == ERR_OK:   # --absent-error 0: read as nothing plugged in (all ones)
                return text, self._read_data(address, size, data=b"\xff" * size)
            return text, self._read_data(address, size, error=where)
        return text, self._read_data(address, size, data=bytes(mem[where:where + size]))


def describe_input(report):
    """One line about an input report, for the log."""
    rid = report[0]
    if rid == 0x20:
        f = report[3]
        return "status: battery 0x%02x%s, LEDs %x, IR %s, no extension" % (
            report[6], " (low)" if f & 1 else "", f >> 4, "on" if f & 8 else "off")
    if rid == 0x21:
        err, size = report[3] & 0x0F, (report[3] >> 4) + 1
        addr = (report[4] << 8) | report[5]
        return "read data at ..%04x: error %d" % (addr, err) if err else "read data: %d bytes at ..%04x" % (size, addr)
    if rid == 0x22:
        return "ack of 0x%02x: %s" % (report[3], "ok" if report[4] == 0 else "error %d" % report[4])
    return "data report 0x%02x" % rid


# ---------------------------------------------------------------------------------------
# The path: keyframes (t seconds from "go", (x, y, size) or None)

class PathError(ValueError):
    pass


class Path:
    def __init__(self, keyframes, loop_from=None):
        if not keyframes:
            raise PathError("a path needs at least one point")
        last = None
        for t, _ in keyframes:
            if last is not None and t < last:
                raise PathError("keyframe times must not decrease (%g after %g)" % (t, last))
            last = t
        self.keyframes = list(keyframes)
        self.loop_from = loop_from   # seconds: after the end, replay from this time

    @property
    def duration(self):
        return self.keyframes[-1][0]

    def start(self):
        return self.keyframes[0][1]

    def position(self, t):
        """The dot at t seconds: (x, y, size) with floats for x, y, or None."""
        kf = self.keyframes
        end = kf[-1][0]
        if self.loop_from is not None and t > end and end > self.loop_from:
            t = self.loop_from + (t - self.loop_from) % (end - self.loop_from)
        if t <= kf[0][0]:
            return kf[0][1]
        if t >= end:
            return kf[-1][1]
        lo, hi = 0, len(kf) - 1
        while hi - lo > 1:              # last keyframe with time <= t
            mid = (lo + hi) // 2
            if kf[mid][0] <= t:
                lo = mid
            else:
                hi = mid
        (t0, a), (t1, b) = kf[lo], kf[hi]
        if a is None:
            return None
        if b is None or t1 <= t0:
            return a
        f = (t - t0) / (t1 - t0)
        return (a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2])

    def script_text(self):
        lines = ["# seconds  x  y  size   (camera pixels; 'none' = no dot)"]
        for t, p in self.keyframes:
            lines.append("%.3f none" % t if p is None else "%.3f %.1f %.1f %d" % (t, p[0], p[1], p[2]))
        return "\n".join(lines) + "\n"


def parse_script(text, name="script", dot_size=4):
    keyframes = []
    for number, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        parts = line.split()
        where = "%s:%d: " % (name, number)
        try:
            t = float(parts[0])
        except ValueError:
            raise PathError(where + "time %r is not a number of seconds" % parts[0]) from None
        if not (t >= 0) or t != t or t == float("inf"):
            raise PathError(where + "time must be a finite number of seconds >= 0")
        if keyframes and t < keyframes[-1][0]:
            raise PathError(where + "time %g is before the previous line's %g" % (t, keyframes[-1][0]))
        if len(parts) == 2 and parts[1].lower() == "none":
            keyframes.append((t, None))
            continue
        if len(parts) not in (3, 4):
            raise PathError(where + "expected 'SECONDS X Y [SIZE]' or 'SECONDS none'")
        try:
            x, y = float(parts[1]), float(parts[2])
            size = int(parts[3]) if len(parts) == 4 else dot_size
        except ValueError:
            raise PathError(where + "X, Y must be numbers and SIZE a whole number") from None
        if not (0 <= x <= 1023 and 0 <= y <= 767):
            raise PathError(where + "(%g, %g) is off the camera (x 0..1023, y 0..767)" % (x, y))
        if not 0 <= size <= 15:
            raise PathError(where + "size %d is not 0..15" % size)
        keyframes.append((t, (x, y, size)))
    if not keyframes:
        raise PathError("%s: no points" % name)
    return Path(keyframes)


class CameraBox:
    """Normalised screen (0..1, y down) -> camera pixels, linearly: the screen's corners (0,0)
    and (1,1) seen at camera (x0, y0) and (x1, y1). x0 > x1 mirrors."""

    def __init__(self, x0, y0, x1, y1):
        self.x0, self.y0, self.x1, self.y1 = x0, y0, x1, y1

    def __call__(self, u, v):
        return (self.x0 + u * (self.x1 - self.x0), self.y0 + v * (self.y1 - self.y0))


def calibration_targets(columns=3, rows=3, margin_x=0.1, margin_y=0.1):
    """The kiosk's targets in reading order (core/calibration_session.cpp, calibration_grid)."""
    return [(margin_x + (1 - 2 * margin_x) * k / (columns - 1), margin_y + (1 - 2 * margin_y) * r / (rows - 1))
            for r in range(rows) for k in range(columns)]


def builtin_path(box, calibration, strokes, dot_size=4, grid=(3, 3), margin=(0.1, 0.1), lead_in=1.5,
                 travel=0.4, dwell=3.0, pause=2.0, bars=(0.27, 0.76), stroke_top=0.35,
                 stroke_bottom=0.75, stroke_rest=1.0, stroke_down=0.12, stroke_hold=0.15,
                 stroke_up=0.4, loop_strokes=False):
    """The calibration's targets and/or strokes as keyframes (see the module doc)."""
    def at(u, v):
        x, y = box(u, v)
        return (x, y, dot_size)

    if calibration:
        rest = at(0.5, 0.5)
    else:
        rest = at(bars[0], stroke_top)
    kf = [(0.0, rest), (lead_in, rest)]
    t = lead_in
    if calibration:
        for u, v in calibration_targets(grid[0], grid[1], margin[0], margin[1]):
            p = at(u, v)
            t += travel
            kf.append((t, p))
            t += dwell
            kf.append((t, p))
        t += pause
        kf.append((t, kf[-1][1]))
    strokes_from = t
    for i in range(strokes):
        u = bars[i % len(bars)]
        top, bottom = at(u, stroke_top), at(u, stroke_bottom)
        if kf[-1][1] != top:
            t += travel
            kf.append((t, top))
        t += stroke_rest
        kf.append((t, top))
        t += stroke_down
        kf.append((t, bottom))
        t += stroke_hold
        kf.append((t, bottom))
        t += stroke_up
        kf.append((t, top))
    return Path(kf, loop_from=strokes_from if (loop_strokes and strokes) else None)


# ---------------------------------------------------------------------------------------
# The device on /dev/uhid

def _log_to_stderr(start):
    def log(msg):
        sys.stderr.write("wiimote_uhid: +%.3f %s\n" % (time.monotonic() - start, msg))
        sys.stderr.flush()
    return log


class Emulator:
    """Runs the model on /dev/uhid (or any fd speaking the same events: the tests' socketpair)."""

    def __init__(self, opts, model, path, open_uhid=None, log=None, clock=time.monotonic):
        self.opts = opts
        self.model = model
        self.path = path
        self.open_uhid = open_uhid or (lambda: os.open(opts.uhid, os.O_RDWR | os.O_CLOEXEC | os.O_NONBLOCK))
        self.log = log or (lambda _m: None)
        self.clock = clock
        self.fd = None
        self.started = self.opened = False
        self.want = {"off": False, "on": False, "go": False, "stop": False}
        self.go_at = None
        self.rng = random.Random(opts.seed)
        self.record = None
        self.sent_data = 0
        self.late_ticks = 0
        self.created_at = None
        self.off_at = None
        self.off_cycle_done = False
        self.startups_at_go = None

    # --- I/O

    def _write(self, event, what):
        if self.fd is None:
            return False
        try:
            os.write(self.fd, event)
            return True
        except OSError as e:
            self.log("error: writing %s to uhid: %s" % (what, e.strerror))
            return False

    def send_input(self, report, now):
        if self._write(pack_input2(report), "input report 0x%02x" % report[0]) and self.record:
            self.record.write("%d %s\n" % (int(now * 1e9), hexs(report)))

    def create(self):
        o = self.opts
        self.fd = self.open_uhid()
        os.set_blocking(self.fd, False)
        self.model.reset()
        self.started = self.opened = False
        name = o.name or ("Nintendo RVL-CNT-01-TR" if o.product == 0x0330 else "Nintendo RVL-CNT-01")
        ok = self._write(pack_create2(name, o.phys, o.uniq, report_descriptor(), BUS_BLUETOOTH, o.vendor, o.product,
                                      o.hid_version, 0), "CREATE2")
        self.created_at = self.clock()
        self.log("switched on: UHID_CREATE2 %s (bus 0x%02x, %04x:%04x, uniq %s)%s" % (
            name, BUS_BLUETOOTH, o.vendor, o.product, o.uniq, "" if ok else " FAILED"))
        return ok

    def destroy(self, why):
        if self.fd is None:
            return
        self._write(pack_destroy(), "DESTROY")
        try:
            os.close(self.fd)
        except OSError:
            pass
        self.fd = None
        self.started = self.opened = False
        self.log("switched off (%s): UHID_DESTROY" % why)

    def _read_events(self, now):
        while self.fd is not None:
            try:
                buf = os.read(self.fd, EVENT_SIZE)
            except BlockingIOError:
                return
            except OSError as e:
                if e.errno == errno.EINTR:
                    continue
                self.log("error: reading uhid: %s" % e.strerror)
                return
            if not buf:
                return
            self.handle_event(buf, now)

    def handle_event(self, buf, now):
        try:
            etype, ev = unpack_event(buf)
        except ValueError as e:
            self.log("error: %s" % e)
            return
        if etype == UHID_START:
            self.started = True
            self.log("kernel: UHID_START (a driver bound it; dev_flags 0x%x)" % ev["dev_flags"])
        elif etype == UHID_STOP:
            self.started = False
            self.log("kernel: UHID_STOP")
        elif etype == UHID_OPEN:
            self.opened = True
            self.log("kernel: UHID_OPEN (someone listens: data reports flow)")
        elif etype == UHID_CLOSE:
            self.opened = False
            self.log("kernel: UHID_CLOSE")
        elif etype == UHID_OUTPUT:
            if ev["rtype"] != UHID_OUTPUT_REPORT:
                self.log("kernel: UHID_OUTPUT of report type %d (%s): ignored" % (ev["rtype"], hexs(ev["data"])))
                return
            for answer in self.model.handle_output(ev["data"]):
                self.send_input(answer, now)
        elif etype == UHID_GET_REPORT:
            self.log("kernel: UHID_GET_REPORT id %d report 0x%02x type %d: the remote has none, EIO" % (
                ev["id"], ev["rnum"], ev["rtype"]))
            self._write(pack_get_report_reply(ev["id"], errno.EIO), "GET_REPORT_REPLY")
        elif etype == UHID_SET_REPORT:
            if ev["rtype"] == UHID_OUTPUT_REPORT and ev["data"]:
                self.log("kernel: UHID_SET_REPORT of an output report: taken as one")
                answers = self.model.handle_output(ev["data"])
                self._write(pack_set_report_reply(ev["id"], 0), "SET_REPORT_REPLY")
                for answer in answers:
                    self.send_input(answer, now)
            else:
                self.log("kernel: UHID_SET_REPORT id %d report 0x%02x type %d: refused, EIO" % (
                    ev["id"], ev["rnum"], ev["rtype"]))
                self._write(pack_set_report_reply(ev["id"], errno.EIO), "SET_REPORT_REPLY")
        else:
            self.log("kernel: uhid event %s (%d): ignored" % (EVENT_NAMES.get(etype, "?"), etype))

    # --- the path

    def dots(self, now):
        if self.go_at is None:
            p = self.path.start()
        else:
            p = self.path.position(now - self.go_at)
        if p is None:
            return []
        j = self.opts.jitter
        x = int(round(p[0] + (self.rng.randint(-j, j) if j else 0)))
        y = int(round(p[1] + (self.rng.randint(-j, j) if j else 0)))
        if not (0 <= x <= 1023 and 0 <= y <= 767):
            return []
        return [(x, y, p[2])]

    def check_go(self, now):
        if self.go_at is not None:
            if self.startups_at_go is not None and self.model.startups > self.startups_at_go:
                self.log("warning: IR start-up #%d after the path started (a reconnect, or the kiosk's "
                         "sensitivity tuner was not done): the path may be out of step; SIGHUP restarts it"
                         % self.model.startups)
                self.startups_at_go = self.model.startups
            return
        o = self.opts
        m = self.model
        why = None
        if self.want["go"]:
            why = "SIGHUP"
        elif o.go_after_startups is not None and o.go_after_startups <= m.startups:
            why = "IR start-up #%d seen" % m.startups if o.go_after_startups else "at once"
        elif o.go_after_switches is not None and o.go_after_switches <= m.switches:
            why = "sensitivity switch #%d seen: the kiosk's tuner is done" % m.switches
        elif o.go_timeout and now - self.t0 >= o.go_timeout:
            why = "--go-timeout %g s passed with %d IR start-up(s)" % (o.go_timeout, self.model.startups)
        if why:
            self.go_at = now
            self.startups_at_go = self.model.startups
            self.log("go (%s): the path starts (%.1f s long)" % (why, self.path.duration))

    # --- the loop

    def run(self, until=None):
        o = self.opts
        self.t0 = self.clock()
        if o.record:
            self.record = open(o.record, "w")
            self.record.write("# mallet-wiimote-replay 1\n# written by wiimote_uhid.py: what the emulated remote sent\n")
        period = 1.0 / o.rate
        next_tick = self.t0
        next_stats = self.t0 + o.stats_every if o.stats_every else None
        next_status = self.t0 + o.status_every if o.status_every else None
        self.create()
        try:
            while True:
                now = self.clock()
                if self.want["stop"] or (until is not None and now >= until) or (
                        o.exit_after and now - self.t0 >= o.exit_after):
                    break
                self._switches(now)
                if self.want["go"] and self.go_at is not None:
                    self.go_at = None           # SIGHUP again: restart the path
                self.check_go(now)
                self.want["go"] = False
                timeout = max(0.0, min(next_tick - now, 0.05))
                if self.fd is not None:
                    p = select.poll()
                    p.register(self.fd, select.POLLIN)
                    p.poll(timeout * 1000)
                    self._read_events(self.clock())
                else:
                    time.sleep(timeout)
                now = self.clock()
                if now >= next_tick:
                    if self.fd is not None and self.started and self.opened:
                        if next_status and now >= next_status:
                            next_status = now + o.status_every
                            report = self.model.unsolicited_status()
                            self.log("-> %s  unsolicited status (--status-every)" % hexs(report))
                            self.send_input(report, now)
                        report = self.model.data_report(self.dots(now))
                        if report is not None:
                            self.send_input(report, now)
                            self.sent_data += 1
                    next_tick += period
                    if now - next_tick > period:      # late (a slow guest): skip, never burst
                        self.late_ticks += int((now - next_tick) / period)
                        next_tick = now + period
                if next_stats and now >= next_stats:
                    next_stats = now + o.stats_every
                    self._stats(now)
        finally:
            self.destroy("exit")
            if self.record:
                self.record.close()

    def _switches(self, now):
        o = self.opts
        if self.want["off"]:
            self.want["off"] = False
            self.destroy("SIGUSR1")
            self.off_at = now
        if self.want["on"]:
            self.want["on"] = False
            if self.fd is None:
                self.create()
            else:
                self.log("SIGUSR2: already on")
        if o.off_after and not self.off_cycle_done and self.fd is not None and self.off_at is None and \
                now - self.created_at >= o.off_after:
            self.destroy("--off-after %g s" % o.off_after)
            self.off_at = now
        if o.on_after and self.fd is None and self.off_at is not None and now - self.off_at >= o.on_after:
            self.off_cycle_done = True
            self.off_at = None
            self.create()

    def _stats(self, now):
        d = self.dots(now)
        m = self.model
        self.log("stats: %d data reports sent, mode 0x%02x %s%s, camera %s (format %d, %s), dot %s, "
                 "IR start-ups %d, late ticks %d, %s" % (
                     self.sent_data, m.mode, "continuous" if m.continuous else "on change",
                     "" if m.reporting else " (stopped by a status report)",
                     "sending" if m.camera_sending else "not sending", m.camera_format, m.sensitivity_name(),
                     "%d,%d" % d[0][:2] if d else "none", m.startups, self.late_ticks,
                     "path at %.1f/%.1f s" % (now - self.go_at, self.path.duration) if self.go_at is not None
                     else "waiting for go (%s; SIGHUP starts now)" % self.waiting_for()))

    def waiting_for(self):
        o, m = self.opts, self.model
        parts = []
        if o.go_after_startups is not None:
            parts.append("IR start-ups %d/%d" % (m.startups, o.go_after_startups))
        if o.go_after_switches is not None:
            parts.append("sensitivity switches %d/%d" % (m.switches, o.go_after_switches))
        if o.go_timeout:
            parts.append("or --go-timeout %g s" % o.go_timeout)
        return ", ".join(parts) or "SIGHUP only"


# ---------------------------------------------------------------------------------------
# Command line

def _floats(text, n, what):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError("%s: expected %d comma-separated numbers" % (what, n)) from None
    if n and len(values) != n:
        raise argparse.ArgumentTypeError("%s: expected %d comma-separated numbers" % (what, n))
    return values


def _int_auto(text):
    return int(text, 0)


def build_parser():
    p = argparse.ArgumentParser(
        prog="wiimote_uhid.py",
        description="Emulate a Wii Remote (RVL-CNT-01) on /dev/uhid for the kernel's hid-wiimote and Mallet "
                    "(the VM system test). Needs root and the uhid module.",
        epilog="Signals: SIGUSR1 switches the remote off (UHID_DESTROY), SIGUSR2 on again (UHID_CREATE2), "
               "SIGHUP starts (or restarts) the path now, SIGINT/SIGTERM stop. Log on stderr.")
    src = p.add_argument_group("the path the IR dot follows")
    src.add_argument("--script", metavar="FILE", help="lines 'SECONDS X Y [SIZE]' or 'SECONDS none' (camera px)")
    src.add_argument("--calibration", action="store_true", help="dwell on the kiosk's calibration targets")
    src.add_argument("--strokes", type=int, default=0, metavar="N", help="downswings through bars (default 0)")
    src.add_argument("--loop", action="store_true", help="repeat the script, or the strokes, forever")
    src.add_argument("--go-after-startups", type=int, default=None, metavar="N",
                     help="start the path once N IR start-ups (camera made to send, then a continuous 0x12) were "
                          "seen (default without --calibration: 1; 0 = at once)")
    src.add_argument("--go-after-switches", type=int, default=None, metavar="N",
                     help="start the path once N of those were sensitivity switches, i.e. not right after a "
                          "connect's status request (default with --calibration: 2 + the index of "
                          "--needs-sensitivity: the kiosk's tuner tried its presets up to the one it chose, "
                          "then set the chosen one)")
    src.add_argument("--go-timeout", type=float, default=0.0, metavar="S",
                     help="start the path after S seconds anyway (default 0: wait for the start-ups or SIGHUP)")
    src.add_argument("--camera-box", type=lambda s: _floats(s, 4, "--camera-box"), default=[162, 134, 862, 634],
                     metavar="X0,Y0,X1,Y1", help="camera px of the screen's corners (0,0) and (1,1) "
                     "(default 162,134,862,634; X0 > X1 mirrors)")
    src.add_argument("--grid", default="3x3", metavar="CxR", help="calibration targets, columns x rows (default 3x3)")
    src.add_argument("--margin", type=float, default=0.1, help="targets' margin, normalised (default 0.1)")
    src.add_argument("--lead-in", type=float, default=1.5, metavar="S", help="rest after go (default 1.5)")
    src.add_argument("--travel", type=float, default=0.4, metavar="S", help="moving to a target or bar (default 0.4)")
    src.add_argument("--dwell", type=float, default=3.0, metavar="S",
                     help="held on each target (default 3.0; the kiosk needs >= 1.7)")
    src.add_argument("--pause", type=float, default=2.0, metavar="S",
                     help="held after the last target, before the strokes (default 2.0)")
    src.add_argument("--bars", type=lambda s: _floats(s, 0, "--bars"), default=[0.27, 0.76], metavar="U,U,...",
                     help="normalised screen x of the bars struck in turn (default 0.27,0.76: a xylophone and "
                          "a glockenspiel bar of the percussion scene)")
    src.add_argument("--stroke-top", type=float, default=0.35, metavar="V", help="screen y above the bars (0.35)")
    src.add_argument("--stroke-bottom", type=float, default=0.75, metavar="V", help="screen y below their tops (0.75)")
    src.add_argument("--stroke-rest", type=float, default=1.0, metavar="S", help="held above a bar (1.0)")
    src.add_argument("--stroke-down", type=float, default=0.12, metavar="S", help="the downswing (0.12)")
    src.add_argument("--stroke-hold", type=float, default=0.15, metavar="S", help="held below (0.15)")
    src.add_argument("--stroke-up", type=float, default=0.4, metavar="S", help="back up (0.4)")
    src.add_argument("--dot-size", type=int, default=4, help="the dot's size 0..15 in extended mode (default 4)")
    src.add_argument("--jitter", type=int, default=1, metavar="PX", help="uniform noise +-PX on each axis (default 1)")
    src.add_argument("--seed", type=int, default=1, help="of the jitter (default 1)")
    src.add_argument("--dump-path", action="store_true", help="print the path as a script and exit")

    dev = p.add_argument_group("the remote")
    dev.add_argument("--uhid", default="/dev/uhid", help="(default /dev/uhid)")
    dev.add_argument("--vendor", type=_int_auto, default=0x057E)
    dev.add_argument("--product", type=_int_auto, default=0x0306, help="0x0306 (default) or 0x0330 (-TR)")
    dev.add_argument("--name", default=None, help="default 'Nintendo RVL-CNT-01' (or '...-TR' for 0x0330)")
    dev.add_argument("--uniq", default="00:19:1d:4d:4c:01",
                     help="its Bluetooth address (hidapi's serial, Mallet's remote identity)")
    dev.add_argument("--phys", default="00:00:00:00:00:00", help="the host adapter's address")
    dev.add_argument("--hid-version", type=_int_auto, default=0x0600, help="CREATE2's version field")
    dev.add_argument("--rate", type=float, default=100.0, help="data reports per second (default 100)")
    dev.add_argument("--battery", type=_int_auto, default=0xC8, help="raw level 0..255 (default 0xc8)")
    dev.add_argument("--battery-low", action="store_true")
    dev.add_argument("--needs-sensitivity", choices=SENSITIVITY_NAMES, default=None,
                     help="the camera sees the dot only with this sensitivity preset or a more sensitive one")
    dev.add_argument("--status-resets", choices=("unsolicited", "all", "none"), default="unsolicited",
                     help="which 0x20 status reports stop data reports until 0x12 (default unsolicited)")
    dev.add_argument("--absent-error", type=int, default=7, metavar="CODE",
                     help="error code of reads and writes of the absent extension and Motion Plus (0xA4xxxx, "
                          "0xA6xxxx), which hid-wiimote polls every 4 s (default 7, as a real remote; 0: acked "
                          "as if written, read as ff ff ...)")
    dev.add_argument("--status-every", type=float, default=0.0, metavar="S",
                     help="send an unsolicited status report every S seconds (default 0: never)")
    dev.add_argument("--off-after", type=float, default=0.0, metavar="S",
                     help="switch off S seconds after switching on (once; default 0: only on SIGUSR1)")
    dev.add_argument("--on-after", type=float, default=0.0, metavar="S",
                     help="switch on again S seconds after switching off (default 0: only on SIGUSR2)")
    dev.add_argument("--exit-after", type=float, default=0.0, metavar="S", help="stop after S seconds (0: never)")
    dev.add_argument("--record", metavar="FILE",
                     help="write every input report sent, Mallet's replay format (mallet wiimote monitor --replay)")
    dev.add_argument("--stats-every", type=float, default=10.0, metavar="S", help="a stats line every S s (0: none)")
    dev.add_argument("--quiet", action="store_true", help="no line per output report (state changes only)")
    dev.add_argument("--print-descriptor", action="store_true", help="print the report descriptor (hex) and exit")
    return p


def make_path(o, parser):
    try:
        cols, rows = (int(v) for v in o.grid.lower().split("x"))
    except ValueError:
        parser.error("--grid: expected COLUMNSxROWS, e.g. 3x3")
    if cols < 2 or rows < 2:
        parser.error("--grid: at least 2x2")
    if o.script:
        if o.calibration or o.strokes:
            parser.error("--script cannot be combined with --calibration or --strokes")
        try:
            with open(o.script) as f:
                path = parse_script(f.read(), o.script, o.dot_size)
        except OSError as e:
            parser.error("--script: %s" % e)
        except PathError as e:
            parser.error(str(e))
        if o.loop:
            path.loop_from = 0.0
        return path
    if not o.calibration and o.strokes <= 0:
        parser.error("say what the camera sees: --script FILE, --calibration and/or --strokes N")
    return builtin_path(CameraBox(*o.camera_box), o.calibration, max(0, o.strokes), o.dot_size, (cols, rows),
                        (o.margin, o.margin), o.lead_in, o.travel, o.dwell, o.pause, o.bars, o.stroke_top,
                        o.stroke_bottom, o.stroke_rest, o.stroke_down, o.stroke_hold, o.stroke_up, o.loop)


def parse_options(argv):
    """(options, path) from the command line, defaults filled in; exits 2 on a usage error."""
    parser = build_parser()
    o = parser.parse_args(argv)
    if o.print_descriptor:
        return o, None
    if not 1 <= o.rate <= 1000:
        parser.error("--rate must be 1..1000")
    if o.strokes < 0:
        parser.error("--strokes must be >= 0")
    if not 0 <= o.absent_error <= 15:
        parser.error("--absent-error must be 0..15")
    if not 0 <= o.dot_size <= 15:
        parser.error("--dot-size must be 0..15")
    if not o.bars or not all(0 <= u <= 1 for u in o.bars):
        parser.error("--bars: normalised screen x positions 0..1")
    path = make_path(o, parser)
    if o.go_after_startups is None and o.go_after_switches is None:
        if o.calibration:
            o.go_after_switches = 2 + (SENSITIVITY_NAMES.index(o.needs_sensitivity) if o.needs_sensitivity else 0)
        else:
            o.go_after_startups = 1
    return o, path


def main(argv=None):
    o, path = parse_options(argv)
    if o.print_descriptor:
        print(hexs(report_descriptor()))
        return 0
    if o.dump_path:
        sys.stdout.write(path.script_text())
        return 0

    start = time.monotonic()
    log = _log_to_stderr(start)
    def model_log(msg):
        # --quiet keeps the state changes: start-ups, warnings, reporting stopped.
        if not o.quiet or "start-up" in msg or "warning" in msg or "stop" in msg:
            log(msg)

    model = WiimoteModel(o.battery, o.battery_low, o.dot_size, o.status_resets, o.needs_sensitivity, log=model_log,
                         absent_error=o.absent_error)
    emulator = Emulator(o, model, path, log=log)

    def on_signal(signum, _frame):
        emulator.want[{signal.SIGUSR1: "off", signal.SIGUSR2: "on", signal.SIGHUP: "go"}.get(signum, "stop")] = True

    for s in (signal.SIGUSR1, signal.SIGUSR2, signal.SIGHUP, signal.SIGINT, signal.SIGTERM):
        signal.signal(s, on_signal)
    log("pid %d: %s; path %.1f s; go: %s" % (
        os.getpid(), " ".join(sys.argv[1:]) if argv is None else " ".join(argv), path.duration,
        emulator.waiting_for()))
    try:
        emulator.run()
    except FileNotFoundError:
        log("error: %s does not exist (modprobe uhid; it needs root)" % o.uhid)
        return 1
    except PermissionError:
        log("error: cannot open %s: permission denied (run as root)" % o.uhid)
        return 1
    log("stopped")
    return 0


if __name__ == "__main__":
    sys.exit(main())
