#!/usr/bin/env python3
"""Runs the shell blocks of README.md and docs/*.md that are marked runnable.

A block is runnable when the line before its opening fence is `<!-- runnable -->` and the
fence is ```sh. Each block runs with `bash -e -o pipefail` in a scratch folder of its own that
holds the checkout's config/, models/ and shaders/ (links), with `build/release/mallet` and
`mallet` on the PATH being the binary under test, as a reader would type it after the
README's first command. A failing block is named by its file and line, with its output.

  usage: run_doc_blocks.py --source CHECKOUT --binary MALLET [--list]
"""
import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

MARKER = "<!-- runnable -->"
TIMEOUT_S = 280


def blocks_of(path, root):
    """Yields (line number of the fence, text) for each runnable block; raises on a marker
    that is not followed by a ```sh block."""
    lines = path.read_text(encoding="utf-8").split("\n")
    name = path.relative_to(root)
    i = 0
    while i < len(lines):
        if lines[i].strip() != MARKER:
            i += 1
            continue
        fence = i + 1
        if fence >= len(lines) or lines[fence].strip() != "```sh":
            raise SystemExit(f"{name}:{fence + 1}: `{MARKER}` must be followed by a ```sh block")
        end = fence + 1
        while end < len(lines) and lines[end].strip() != "```":
            end += 1
        if end == len(lines):
            raise SystemExit(f"{name}:{fence + 1}: the runnable block is never closed")
        body = "\n".join(lines[fence + 1:end])
        if not body.strip():
            raise SystemExit(f"{name}:{fence + 1}: the runnable block is empty")
        yield fence + 1, body + "\n"
        i = end + 1


def scratch_for(source, binary):
    work = pathlib.Path(tempfile.mkdtemp(prefix="mallet-doc-"))
    for d in ("config", "models", "shaders"):
        (work / d).symlink_to(source / d)
    (work / "build" / "release").mkdir(parents=True)
    (work / "build" / "release" / "mallet").symlink_to(binary)
    return work


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True, type=pathlib.Path)
    ap.add_argument("--binary", required=True, type=pathlib.Path)
    ap.add_argument("--list", action="store_true", help="print the blocks, run nothing")
    args = ap.parse_args()
    source = args.source.resolve()
    binary = args.binary.resolve()
    files = [source / "README.md"] + sorted((source / "docs").glob("*.md"))
    found = [(f, line, body) for f in files for line, body in blocks_of(f, source)]
    if not found:
        print("no runnable blocks found in README.md or docs/*.md", file=sys.stderr)
        return 1
    failed = 0
    for f, line, body in found:
        where = f"{f.relative_to(source)}:{line}"
        if args.list:
            print(f"--- {where}\n{body}", end="")
            continue
        work = scratch_for(source, binary)
        env = dict(os.environ)
        env["PATH"] = f"{work / 'build' / 'release'}{os.pathsep}{env.get('PATH', '')}"
        try:
            run = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", body], cwd=work, env=env,
                                 stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                 timeout=TIMEOUT_S)
            status, output = run.returncode, run.stdout
        except subprocess.TimeoutExpired as e:
            status, output = "timed out", (e.stdout or b"").decode(errors="replace") if isinstance(e.stdout, bytes) else (e.stdout or "")
        if status == 0:
            print(f"ok    {where}")
            shutil.rmtree(work, ignore_errors=True)
        else:
            failed += 1
            tail = "\n".join(output.splitlines()[-30:])
            print(f"FAIL  {where}: the block exited {status} (scratch folder kept: {work})\n{body}--- its output:\n{tail}")
    if args.list:
        return 0
    print(f"{len(found) - failed} of {len(found)} runnable blocks in {len({f for f, _, _ in found})} files ran")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
