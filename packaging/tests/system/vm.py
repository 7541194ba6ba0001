"""The test machine: a Debian 12 or 13 guest in QEMU, driven only through what a museum has.

- the screen: QMP `screendump` (PPM, read here; written out as PNG for people to look at);
- the mouse and the keyboard: QMP `input-send-event` to a USB mouse and keyboard;
- the speaker: QEMU's WAV audio back-end behind an emulated Intel HDA card;
- a shell: the QEMU guest agent (`guest-exec`), for journalctl, systemctl and mallet doctor.

Python's standard library only (the CI machine installs nothing for it).
"""

import base64
import json
import os
import socket
import struct
import subprocess
import time
import wave
import zlib


class VmError(Exception):
    """A check's failure, said in one line."""


class Qmp:
    """QEMU's machine protocol on a UNIX socket: one command at a time, events skipped."""

    def __init__(self, path, timeout=30):
        deadline = time.monotonic() + timeout
        while True:
            try:
                self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
                self.sock.connect(path)
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise VmError(f"QMP: no socket at {path}")
                time.sleep(0.2)
        self.sock.settimeout(60)
        self.file = self.sock.makefile("rwb")
        self._read()  # the greeting
        self.execute("qmp_capabilities")

    def _read(self):
        while True:
            line = self.file.readline()
            if not line:
                raise VmError("QMP: QEMU closed the connection")
            message = json.loads(line)
            if "event" not in message:
                return message

    def execute(self, command, **arguments):
        request = {"execute": command}
        if arguments:
            request["arguments"] = arguments
        self.file.write(json.dumps(request).encode() + b"\n")
        self.file.flush()
        reply = self._read()
        if "error" in reply:
            raise VmError(f"QMP {command}: {reply['error'].get('desc', reply['error'])}")
        return reply.get("return")

    # --- the mouse and the keyboard ---
    def move(self, dx, dy):
        """Moves the USB mouse by (dx, dy) counts, in steps of at most 100: a USB mouse's report
        carries at most ±127 a axis, and QEMU's usb-mouse clamps a larger motion to that (seen:
        the mallet never left the screen's left edge)."""
        dx, dy = int(dx), int(dy)
        while dx or dy:
            sx = max(-100, min(100, dx))
            sy = max(-100, min(100, dy))
            events = []
            if sx:
                events.append({"type": "rel", "data": {"axis": "x", "value": sx}})
            if sy:
                events.append({"type": "rel", "data": {"axis": "y", "value": sy}})
            self.execute("input-send-event", events=events)
            dx -= sx
            dy -= sy

    def keys(self, *names, hold=0.1):
        """Presses the keys (QEMU qcodes: "ctrl", "alt", "o", "q", "d"…) together, then
        releases them in reverse order."""
        for name in names:
            self.execute("input-send-event",
                         events=[{"type": "key", "data": {"down": True, "key": {"type": "qcode", "data": name}}}])
        time.sleep(hold)
        for name in reversed(names):
            self.execute("input-send-event",
                         events=[{"type": "key", "data": {"down": False, "key": {"type": "qcode", "data": name}}}])

    def screendump(self, path):
        self.execute("screendump", filename=path)
        return read_ppm(path)


class Agent:
    """The QEMU guest agent (qemu-guest-agent in the guest) on its virtio-serial port."""

    def __init__(self, path):
        self.path = path
        self.sock = None
        self.sync_id = int(time.time()) & 0xFFFFFF

    def connect(self, timeout):
        """Waits until the agent answers (the guest has booted this far); False on time-out."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                self._reconnect()
                self.sync_id += 1
                # 0xFF resets the agent's JSON parser: a client that went away mid-request (a
                # killed test) leaves half a command in it.
                self.sock.sendall(b"\xff")
                self._send({"execute": "guest-sync-delimited", "arguments": {"id": self.sync_id}})
                self.sock.settimeout(5)
                buffer = b""
                while True:
                    chunk = self.sock.recv(4096)
                    if not chunk:
                        raise OSError("closed")
                    buffer += chunk
                    if b"\xff" in buffer:
                        buffer = buffer[buffer.rindex(b"\xff") + 1:]
                    if buffer.endswith(b"\n"):
                        for line in buffer.splitlines():
                            try:
                                if json.loads(line).get("return") == self.sync_id:
                                    self.sock.settimeout(180)
                                    self.rest = b""
                                    return True
                            except ValueError:
                                pass
                        buffer = b""
            except (OSError, socket.timeout):
                time.sleep(1)
        return False

    def _reconnect(self):
        if self.sock:
            self.sock.close()
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.connect(self.path)

    def _send(self, request):
        self.sock.sendall(json.dumps(request).encode() + b"\n")

    def call(self, command, **arguments):
        request = {"execute": command}
        if arguments:
            request["arguments"] = arguments
        self._send(request)
        while b"\n" not in self.rest:
            try:
                chunk = self.sock.recv(65536)
            except socket.timeout:
                raise VmError(f"guest agent: no answer to {command} within 180 s")
            if not chunk:
                raise VmError(f"guest agent: connection closed during {command}")
            self.rest += chunk
        line, self.rest = self.rest.split(b"\n", 1)
        reply = json.loads(line.lstrip(b"\xff"))
        if "error" in reply:
            raise VmError(f"guest agent {command}: {reply['error'].get('desc', reply['error'])}")
        return reply.get("return")

    def run(self, command, timeout=120, check=False):
        """Runs a shell command line in the guest as root; returns (status, stdout+stderr)."""
        pid = self.call("guest-exec", path="/bin/sh", arg=["-c", command], **{"capture-output": True})["pid"]
        deadline = time.monotonic() + timeout
        while True:
            status = self.call("guest-exec-status", pid=pid)
            if status.get("exited"):
                break
            if time.monotonic() > deadline:
                raise VmError(f"guest: `{command}` still running after {timeout} s")
            time.sleep(0.3)
        out = base64.b64decode(status.get("out-data", "")).decode(errors="replace")
        err = base64.b64decode(status.get("err-data", "")).decode(errors="replace")
        code = status.get("exitcode", -1 if "signal" in status else 0)
        if check and code != 0:
            raise VmError(f"guest: `{command}` exited {code}: {(out + err).strip()[-400:]}")
        return code, out + err

    def shutdown(self, mode):
        """guest-shutdown sends no reply: the connection is left to the reboot."""
        self._send({"execute": "guest-shutdown", "arguments": {"mode": mode}})


def read_ppm(path):
    """(width, height, RGB bytes) of a binary PPM (P6, maxval 255), QEMU's screendump."""
    with open(path, "rb") as f:
        data = f.read()
    fields = []
    pos = 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    if fields[0] != b"P6" or fields[3] != b"255":
        raise VmError(f"{path}: not a P6 PPM with maxval 255")
    width, height = int(fields[1]), int(fields[2])
    return width, height, data[pos + 1:pos + 1 + width * height * 3]


def write_png(path, width, height, rgb):
    """An RGB PNG (8 bits per channel, no filter): what people open to look at a screen."""
    rows = b"".join(b"\x00" + rgb[y * width * 3:(y + 1) * width * 3] for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(rows, 6)))
        f.write(chunk(b"IEND", b""))


def signature(width, height, rgb, columns=16, rows=9):
    """The screen as a grid of mean colours: what a loose comparison compares."""
    cells = []
    for r in range(rows):
        for c in range(columns):
            x0, x1 = c * width // columns, (c + 1) * width // columns
            y0, y1 = r * height // rows, (r + 1) * height // rows
            total = [0, 0, 0]
            count = 0
            for y in range(y0, y1, 4):
                line = rgb[(y * width + x0) * 3:(y * width + x1) * 3]
                for i in range(0, len(line), 12):
                    total[0] += line[i]
                    total[1] += line[i + 1]
                    total[2] += line[i + 2]
                    count += 1
            cells.append([round(t / max(count, 1)) for t in total])
    return cells


def signature_distance(a, b):
    """Mean absolute difference of two signatures, per colour channel (0–255)."""
    if len(a) != len(b):
        return 255.0
    return sum(abs(x - y) for p, q in zip(a, b) for x, y in zip(p, q)) / (3 * len(a))


def wav_channels_energy(path, since_s=0.0):
    """(rate, left RMS, right RMS) of QEMU's WAV output from `since_s` on. QEMU writes the
    header's sizes when it closes the file, so the samples are read past the header."""
    with open(path, "rb") as f:
        header = f.read(44)
        if len(header) < 44 or header[:4] != b"RIFF":
            raise VmError(f"{path}: not a WAV file")
        channels, rate = struct.unpack("<HI", header[22:28])
        bits = struct.unpack("<H", header[34:36])[0]
        if channels != 2 or bits != 16:
            raise VmError(f"{path}: {channels} channels of {bits} bits, expected 2 of 16")
        f.seek(44 + int(since_s * rate) * 4)
        data = f.read()
    frames = len(data) // 4
    if frames == 0:
        return rate, 0.0, 0.0
    samples = struct.unpack(f"<{frames * 2}h", data[:frames * 4])
    left = (sum(s * s for s in samples[0::2]) / frames) ** 0.5
    right = (sum(s * s for s in samples[1::2]) / frames) ** 0.5
    return rate, left, right


def wav_seconds(path):
    """How many seconds QEMU has written so far."""
    with open(path, "rb") as f:
        header = f.read(44)
    if len(header) < 44:
        return 0.0
    rate = struct.unpack("<I", header[24:28])[0]
    return max(0, os.path.getsize(path) - 44) / 4 / rate


class Machine:
    """One boot of the image: QEMU with the museum's devices, and the sockets to drive it."""

    def __init__(self, image_dir, out_dir, accel, screen=(1024, 576)):
        self.image_dir = image_dir
        self.out = out_dir
        self.accel = accel
        self.screen = screen
        self.process = None
        self.qmp = None
        self.agent = None
        self.wav = os.path.join(out_dir, "audio.wav")

    def command(self):
        d = self.image_dir
        accel = "kvm" if self.accel == "kvm" else "tcg,thread=multi"
        return [
            "qemu-system-x86_64",
            # no PS/2 controller: QMP's USB mouse is the only mouse, as on a kiosk PC
            "-machine", "pc,i8042=off", "-accel", accel, "-cpu", "max", "-smp", "2", "-m", "2048",
            "-kernel", os.path.join(d, "vmlinuz"), "-initrd", os.path.join(d, "initrd.img"),
            "-append", "root=/dev/vda rw console=ttyS0 systemd.show_status=1",
            "-drive", f"file={os.path.join(self.out, 'disk.qcow2')},if=virtio,format=qcow2",
            # a DRM/KMS display (virtio-gpu without 3D: a GPU-less PC's case)
            "-vga", "none", "-device", f"virtio-vga,xres={self.screen[0]},yres={self.screen[1]}",
            "-display", "none",
            # the sound card, its output into a WAV file (both channels: actuator and speaker)
            "-audiodev", f"wav,id=snd0,path={self.wav}",
            "-device", "intel-hda", "-device", "hda-output,audiodev=snd0",
            "-device", "qemu-xhci", "-device", "usb-mouse", "-device", "usb-kbd",
            "-nic", "none",
            "-serial", f"file:{os.path.join(self.out, 'console.log')}",
            "-qmp", f"unix:{os.path.join(self.out, 'qmp.sock')},server=on,wait=off",
            "-chardev", f"socket,path={os.path.join(self.out, 'qga.sock')},server=on,wait=off,id=qga0",
            "-device", "virtio-serial", "-device", "virtserialport,chardev=qga0,name=org.qemu.guest_agent.0",
        ]

    def start(self):
        overlay = os.path.join(self.out, "disk.qcow2")
        if not os.path.exists(overlay):
            subprocess.run(["qemu-img", "create", "-q", "-f", "qcow2", "-F", "raw", "-b",
                            os.path.join(self.image_dir, "disk.raw"), overlay], check=True)
        for name in ("qmp.sock", "qga.sock"):
            try:
                os.unlink(os.path.join(self.out, name))
            except FileNotFoundError:
                pass
        log = open(os.path.join(self.out, "qemu.log"), "ab")
        self.started = time.monotonic()
        self.process = subprocess.Popen(self.command(), stdout=log, stderr=subprocess.STDOUT)
        self.qmp = Qmp(os.path.join(self.out, "qmp.sock"))
        self.agent = Agent(os.path.join(self.out, "qga.sock"))

    def attach(self):
        """The sockets of a machine that is already running."""
        self.started = time.monotonic()
        self.qmp = Qmp(os.path.join(self.out, "qmp.sock"))
        self.agent = Agent(os.path.join(self.out, "qga.sock"))

    def wait_for_agent(self, timeout):
        if not self.agent.connect(timeout):
            raise VmError(f"the guest agent did not answer within {timeout} s of power-on "
                          f"(console: {os.path.join(self.out, 'console.log')})")
        return time.monotonic() - self.started

    def stop(self):
        if self.process and self.process.poll() is None:
            try:
                self.qmp.execute("quit")
            except Exception:
                pass
            try:
                self.process.wait(20)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
