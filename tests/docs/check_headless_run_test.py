#!/usr/bin/env python3
"""tools/check_headless_run.py, which CI runs on the README's first command, refuses what it
must: a blank screenshot, a silent WAV, an empty log, a file the run did not say it wrote; and
passes a run that wrote all three.

    check_headless_run_test.py --source DIR
"""
import argparse
import struct
import subprocess
import sys
import tempfile
import zlib
from pathlib import Path


def png(path: Path, rows: list[bytes], width: int) -> None:
    """An 8-bit RGB PNG; each row filtered with Sub (type 1), as encoders often do."""
    raw = bytearray()
    for row in rows:
        raw.append(1)
        raw += bytes((row[i] - (row[i - 3] if i >= 3 else 0)) & 0xFF for i in range(len(row)))

    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    header = struct.pack(">IIBBBBB", width, len(rows), 8, 2, 0, 0, 0)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(bytes(raw)))
                     + chunk(b"IEND", b""))


def wav(path: Path, samples: list[int]) -> None:
    """16-bit stereo at 48 kHz; samples interleaved."""
    data = struct.pack(f"<{len(samples)}h", *samples)
    fmt = struct.pack("<HHIIHH", 1, 2, 48000, 48000 * 4, 4, 16)
    path.write_bytes(b"RIFF" + struct.pack("<I", 4 + 8 + len(fmt) + 8 + len(data)) + b"WAVE"
                     + b"fmt " + struct.pack("<I", len(fmt)) + fmt + b"data" + struct.pack("<I", len(data)) + data)


def run(checker: Path, folder: Path, names: list[str]) -> subprocess.CompletedProcess:
    log = folder / "run.log"
    log.write_text("mallet run: headless\n" + "".join(f"wrote {folder / n}\n" for n in names))
    return subprocess.run([sys.executable, str(checker), str(log)], capture_output=True, text=True)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--source", required=True, type=Path)
    checker = parser.parse_args().source / "tools" / "check_headless_run.py"
    failures = []
    with tempfile.TemporaryDirectory() as scratch:
        good, bad = Path(scratch) / "good", Path(scratch) / "bad"
        good.mkdir()
        bad.mkdir()
        width = 8
        lit = [bytes([10, 20, 30] * width)] * 7 + [bytes([10, 20, 30] * (width - 1) + [200, 210, 220])]
        png(good / "screenshot.png", lit, width)
        wav(good / "audio.wav", [0, 0, 1200, -800, 0, 0])
        (good / "log.txt").write_text("t=0.500000000 strike bar 3\n")
        png(bad / "screenshot.png", [bytes([10, 20, 30] * width)] * 8, width)
        wav(bad / "audio.wav", [0] * 8)
        (bad / "log.txt").write_text("")

        names = ["screenshot.png", "audio.wav", "log.txt"]
        ok = run(checker, good, names)
        if ok.returncode != 0 or ok.stdout.count("first run:") != 3:
            failures.append(f"a good run was refused (exit {ok.returncode}): {ok.stdout}{ok.stderr}")
        refused = run(checker, bad, names)
        for expected in ("blank (8x8, one colour)", "0 samples not silent", "log.txt: missing or empty"):
            if refused.returncode != 1 or expected not in refused.stderr:
                failures.append(f"a bad run's '{expected}' was not said (exit {refused.returncode}): {refused.stderr}")
        missing = run(checker, good, names[:2])
        if missing.returncode != 1 or "did not say it wrote log.txt" not in missing.stderr:
            failures.append(f"a file the run did not name passed (exit {missing.returncode}): {missing.stderr}")
    for f in failures:
        print(f"check_headless_run: {f}", file=sys.stderr)
    if not failures:
        print("check_headless_run: a good run passes; a blank screenshot, a silent WAV, an empty log and an unnamed file are refused")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
