#!/usr/bin/env python3
"""Checks what the README's first command wrote when it ran the kiosk without a display.

    tools/check_headless_run.py LOG

LOG is what the command printed. `mallet run` headless ends with one line per file it wrote
("wrote DIR/screenshot.png", "wrote DIR/audio.wav", "wrote DIR/log.txt"). Each must be there:
the screenshot a PNG that is not blank (more than one colour), the WAV a stereo RIFF file with
samples that are not all silent, the log a text with at least one line. Prints one line per
file and exits 0, or prints what is wrong (one line each) and exits 1. .ci/run calls it after
the first command.
"""
import struct
import sys
import zlib
from pathlib import Path

WANTED = ("screenshot.png", "audio.wav", "log.txt")


def png_colours(path: Path) -> tuple[int, int, int]:
    """Width, height and the number of distinct pixels (capped at 2) of an 8-bit PNG."""
    data = path.read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG (no signature)")
    pos, idat, header = 8, bytearray(), None
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + length
    if header is None:
        raise ValueError("no IHDR chunk")
    width, height, depth, colour, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace != 0:
        raise ValueError(f"bit depth {depth}, colour type {colour}, interlace {interlace}: not what mallet writes")
    raw = zlib.decompress(bytes(idat))
    stride = width * channels
    if len(raw) != height * (stride + 1):
        raise ValueError(f"{len(raw)} bytes of pixel data for {width}x{height}")
    previous = bytearray(stride)
    first, distinct = None, 1
    for row in range(height):
        kind = raw[row * (stride + 1)]
        line = bytearray(raw[row * (stride + 1) + 1:(row + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            corner = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 0xFF
            elif kind == 2:
                line[i] = (line[i] + up) & 0xFF
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 0xFF
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 0xFF
            elif kind != 0:
                raise ValueError(f"row {row}: filter type {kind}")
        if first is None:
            first = bytes(line[:channels])
        if distinct == 1 and line != first * width:
            distinct = 2
        previous = line
    return width, height, distinct


def wav_summary(path: Path) -> tuple[int, int, int]:
    """Channels, frames, and the number of samples that are not zero (16-bit or float PCM)."""
    data = path.read_bytes()
    if data[:4] != b"RIFF" or data[8:12] != b"WAVE":
        raise ValueError("not a RIFF WAVE file")
    pos, fmt, samples = 12, None, None
    while pos + 8 <= len(data):
        kind, length = struct.unpack("<4sI", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"fmt ":
            fmt = struct.unpack("<HHIIHH", body[:16])
        elif kind == b"data":
            samples = body
        pos += 8 + length + (length & 1)
    if fmt is None or samples is None:
        raise ValueError("no fmt or data chunk")
    _, channels, _, _, block, bits = fmt
    frames = len(samples) // block if block else 0
    width = bits // 8
    nonzero = sum(1 for i in range(0, len(samples) - width + 1, width) if any(samples[i:i + width]))
    return channels, frames, nonzero


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    log = Path(sys.argv[1])
    wrote = {}
    for line in log.read_text(errors="replace").splitlines():
        if line.startswith("wrote "):
            path = Path(line[len("wrote "):].strip())
            wrote[path.name] = path
    problems = []
    for name in WANTED:
        path = wrote.get(name)
        if path is None:
            problems.append(f"{log}: no \"wrote …/{name}\" line: the headless run did not say it wrote {name}")
            continue
        if not path.is_file() or path.stat().st_size == 0:
            problems.append(f"{path}: missing or empty")
            continue
        try:
            if name.endswith(".png"):
                width, height, distinct = png_colours(path)
                if distinct < 2:
                    problems.append(f"{path}: blank ({width}x{height}, one colour)")
                else:
                    print(f"first run: {path}: {width}x{height}, not blank")
            elif name.endswith(".wav"):
                channels, frames, nonzero = wav_summary(path)
                if channels != 2 or frames == 0 or nonzero == 0:
                    problems.append(f"{path}: {channels} channels, {frames} frames, {nonzero} samples not silent")
                else:
                    print(f"first run: {path}: {channels} channels, {frames} frames, {nonzero} samples not silent")
            else:
                lines = path.read_text(errors="replace").splitlines()
                if not lines:
                    problems.append(f"{path}: no line")
                else:
                    print(f"first run: {path}: {len(lines)} lines")
        except (ValueError, zlib.error, struct.error) as e:
            problems.append(f"{path}: {e}")
    for p in problems:
        print(f"first run: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
