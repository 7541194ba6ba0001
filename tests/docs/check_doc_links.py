#!/usr/bin/env python3
"""Checks that every relative link in README.md and docs/*.md points at a file that exists
and, with a #fragment, at a heading of that file (GitHub's anchors). Prints FILE:LINE: problem
for each broken link and exits 1 if there is one.

  usage: check_doc_links.py --source CHECKOUT
"""
import argparse
import pathlib
import re
import sys

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = heading.strip().lower().replace("`", "")
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors_of(path):
    found, fenced = set(), False
    for line in path.read_text(encoding="utf-8").split("\n"):
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and (m := re.match(r"#{1,6}\s+(.*)", line)):
            found.add(slug(m.group(1)))
    return found


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True, type=pathlib.Path)
    source = ap.parse_args().source.resolve()
    files = [source / "README.md"] + sorted((source / "docs").glob("*.md"))
    broken, count = [], 0
    for f in files:
        fenced = False
        for n, line in enumerate(f.read_text(encoding="utf-8").split("\n"), 1):
            if line.startswith("```"):
                fenced = not fenced
            if fenced:
                continue
            for target in LINK.findall(line):
                if re.match(r"[a-z]+:", target):  # http:, https:, mailto:
                    continue
                count += 1
                path, _, fragment = target.partition("#")
                dest = (f.parent / path).resolve() if path else f
                where = f"{f.relative_to(source)}:{n}"
                if not dest.exists():
                    broken.append(f"{where}: {target}: no such file")
                elif fragment and dest.suffix == ".md" and fragment not in anchors_of(dest):
                    broken.append(f"{where}: {target}: no heading #{fragment} in {dest.relative_to(source)}")
    for b in broken:
        print(b)
    print(f"{count - len(broken)} of {count} relative links in {len(files)} files resolve")
    return 1 if broken or count == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
