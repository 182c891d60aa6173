#!/usr/bin/env python3
"""scripts/check_docs.py — the README and the pages it leads to hold together.

  scripts/check_docs.py [--root DIR]

Exit 1, naming file and line, when
  - a relative Markdown link in any .md file of the tree (outside node_modules and build folders)
    names a file or folder that does not exist, or a #fragment no heading of the target gives
    (GitHub's anchors: lower case, punctuation dropped, spaces to hyphens, -1, -2 for repeats);
  - README.md's Quick start no longer holds the test command `.ci/run` runs, character for
    character (CI runs what a newcomer is told to run, and nothing else);
  - README.md is longer than --max-readme-lines (300): it is a newcomer's page, and run logs,
    generated tables and long how-to belong in the pages it links.
Links inside code (fenced blocks, `spans`) and to other sites are not followed.
"""

import argparse
import os
import pathlib
import re
import sys
import unicodedata

SKIP_DIRS = {"node_modules", ".git"}
LINK = re.compile(r"(?<!!)\[(?:[^\]\\]|\\.)*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)|!\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def markdown_files(root):
    for d, dirs, files in os.walk(root):
        rel = pathlib.Path(d).relative_to(root)
        # Build folders hold copies and generated pages; the top-level build/ and any build-* beside it.
        dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not (rel == pathlib.Path(".") and x.startswith("build"))]
        for f in files:
            if f.endswith(".md"):
                yield pathlib.Path(d) / f


def prose_lines(text, keep_code=False):
    """(line number, line) outside fenced code blocks; inline code emptied unless keep_code."""
    fence = None
    for n, line in enumerate(text.splitlines(), 1):
        m = re.match(r"^\s*(```+|~~~+)", line)
        if m:
            if fence is None:
                fence = m.group(1)[0] * 3
            elif m.group(1).startswith(fence):
                fence = None
            continue
        if fence is None:
            yield n, line if keep_code else re.sub(r"`+[^`]*`+", "``", line)


def slug(heading):
    """GitHub's anchor for a heading's text."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link's text only
    text = text.replace("`", "").strip().lower()
    out = []
    for ch in text:
        cat = unicodedata.category(ch)
        if ch in "-_" or cat[0] in "LN" or cat == "Mn":
            out.append(ch)
        elif ch == " ":
            out.append("-")
    return "".join(out)


_anchors = {}


def anchors(path):
    """The #fragments a Markdown file gives: its headings' anchors and explicit HTML anchors."""
    if path not in _anchors:
        text = path.read_text(errors="replace")
        seen, found = {}, set()
        for _, line in prose_lines(text, keep_code=True):
            m = HEADING.match(line)
            if m:
                s = slug(m.group(2))
                k = seen.get(s, 0)
                seen[s] = k + 1
                found.add(s if k == 0 else f"{s}-{k}")
        found |= set(re.findall(r"<a\s+(?:name|id)=\"([^\"]+)\"", text))
        _anchors[path] = found
    return _anchors[path]


def check_links(root):
    problems = []
    for md in sorted(markdown_files(root)):
        for n, line in prose_lines(md.read_text(errors="replace")):
            for m in LINK.finditer(line):
                target = m.group(1) or m.group(2)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:
                    continue
                path_part, _, frag = target.partition("#")
                dest = md if not path_part else (md.parent / path_part)
                where = f"{md.relative_to(root)}:{n}"
                if not dest.exists():
                    problems.append(f"{where}: link to {target}: {path_part} does not exist")
                    continue
                if frag and dest.is_file() and dest.suffix == ".md" and frag not in anchors(dest.resolve()):
                    problems.append(f"{where}: link to {target}: no heading of {dest.name} gives #{frag}")
    return problems


def check_readme(root, max_lines):
    problems = []
    readme = (root / "README.md").read_text()
    ci = root / ".ci" / "run"
    commands = [l.strip() for l in ci.read_text().splitlines() if l.strip() and not l.lstrip().startswith("#")]
    run = [c for c in commands if "ctest" in c]
    if len(run) != 1:
        problems.append(f".ci/run: expected one command line that runs ctest, found {len(run)}")
    else:
        quick = readme.split("## Quick start", 1)[-1].split("\n## ", 1)[0] if "## Quick start" in readme else ""
        if not quick:
            problems.append("README.md: no '## Quick start' section")
        elif run[0] not in [l.strip() for l in quick.splitlines()]:
            problems.append(f"README.md: the Quick start does not hold .ci/run's command, as a line of its own: {run[0]}")
    lines = readme.count("\n") + (0 if readme.endswith("\n") else 1)
    if lines > max_lines:
        problems.append(f"README.md: {lines} lines, more than {max_lines}: move the detail to the page it belongs to and link it")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", type=pathlib.Path, default=pathlib.Path(__file__).resolve().parent.parent,
                    help="the source tree (default: this script's)")
    ap.add_argument("--max-readme-lines", type=int, default=300)
    a = ap.parse_args()
    root = a.root.resolve()
    if not (root / "README.md").is_file():
        sys.exit(f"check_docs.py: {root} has no README.md")
    problems = check_links(root) + check_readme(root, a.max_readme_lines)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
