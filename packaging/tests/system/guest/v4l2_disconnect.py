#!/usr/bin/env python3
"""Presses the kernel's vivid driver's "Disconnect" button on a video node: vivid then acts
as a USB camera pulled out (its buffers fail, poll says error) until every open handle is
closed, when it is there again. The system test unplugs the kiosk's camera with it.

    v4l2_disconnect.py /dev/video0

Finds the control by its name (VIDIOC_QUERYCTRL over every control), so it does not depend
on vivid's private control numbers. Exit 0 when pressed, 1 when the node has no such control.
"""
import fcntl
import os
import struct
import sys

VIDIOC_QUERYCTRL = 0xC0445624  # _IOWR('V', 36, struct v4l2_queryctrl), 68 bytes
VIDIOC_S_CTRL = 0xC008561C     # _IOWR('V', 28, struct v4l2_control), 8 bytes
NEXT_CTRL = 0x80000000
QUERYCTRL = struct.Struct("=II32siiiiI8x")


def controls(fd):
    """(id, name) of every control of the node."""
    cid = NEXT_CTRL
    while True:
        buf = bytearray(QUERYCTRL.pack(cid, 0, b"", 0, 0, 0, 0, 0))
        try:
            fcntl.ioctl(fd, VIDIOC_QUERYCTRL, buf)
        except OSError:
            return
        got, _, name, *_ = QUERYCTRL.unpack(buf)
        yield got, name.split(b"\0", 1)[0].decode(errors="replace")
        cid = got | NEXT_CTRL


def main():
    node = sys.argv[1] if len(sys.argv) > 1 else "/dev/video0"
    fd = os.open(node, os.O_RDWR)
    try:
        for cid, name in controls(fd):
            if name.lower() == "disconnect":
                fcntl.ioctl(fd, VIDIOC_S_CTRL, bytearray(struct.pack("=Ii", cid, 1)))
                print(f"{node}: pressed {name} (0x{cid:08x})")
                return 0
        print(f"{node}: no Disconnect control (is it vivid?)", file=sys.stderr)
        return 1
    finally:
        os.close(fd)


if __name__ == "__main__":
    sys.exit(main())
