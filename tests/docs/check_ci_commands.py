#!/usr/bin/env python3
"""CI runs the README's two commands as the README prints them.

    check_ci_commands.py --source DIR

Reads the two shell blocks under README.md's "## The two commands" heading (their lines that
are not comments: the first command, then the second) and fails, with one line naming the file
and the line, unless .ci/run holds each of them as a line of its own, exactly, the first
before the second.
"""
import argparse
import sys
from pathlib import Path


def readme_commands(readme: Path) -> list[tuple[int, str]]:
    """(line number, command) of each block's command under the two commands' heading."""
    commands, in_section, in_block = [], False, False
    for number, line in enumerate(readme.read_text().splitlines(), start=1):
        if line.startswith("## "):
            in_section = line.strip() == "## The two commands"
            continue
        if not in_section:
            continue
        if line.startswith("```"):
            in_block = not in_block
            continue
        if in_block and line.strip() and not line.lstrip().startswith("#"):
            commands.append((number, line.strip()))
    return commands


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", required=True, type=Path)
    source = parser.parse_args().source
    readme, ci = source / "README.md", source / ".ci/run"
    commands = readme_commands(readme)
    if len(commands) != 2:
        print(f"{readme}: {len(commands)} commands under \"## The two commands\", expected 2: "
              f"{[c for _, c in commands]}", file=sys.stderr)
        return 1
    ci_lines = [line.strip() for line in ci.read_text().splitlines()]
    where = []
    for number, command in commands:
        if command not in ci_lines:
            print(f"{readme}:{number}: .ci/run does not run this command as written: {command}", file=sys.stderr)
            return 1
        where.append(ci_lines.index(command) + 1)
        print(f"{readme}:{number}: .ci/run:{where[-1]} runs it: {command}")
    if where[0] > where[1]:
        print(f"{ci}:{where[0]}: the first command runs after the second (line {where[1]})", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
