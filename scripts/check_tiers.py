#!/usr/bin/env python3
"""scripts/check_tiers.py — the deep tier repeats checks; it never holds one alone.

  scripts/check_tiers.py --build build/release [--doc docs/testing.md]

The tests labelled "deep" (cmake/TestTiers.cmake) are left out of the default tier, which the
Quick start and CI run. Each must appear in the table of docs/testing.md's "The deep tier" section,
as `its name` in the first column, with the default-tier tests that run the same check in the last
column (`names`, one or more). Exit 1, naming each problem, when
  - a deep test has no row, or a row names a test that is not deep or does not exist;
  - a row's last column names no test, or a test that is deep or does not exist;
so that dropping a check from the default run takes a row that says where it still runs.
Exit 4 when the build folder's tests cannot be listed or the page has no such table.
"""

import argparse
import pathlib
import re
import shutil
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from test_times import read_labels  # noqa: E402  (the one listing of a build's tests and labels)

NAME = re.compile(r"`([^`]+)`")


def deep_table(doc):
    """{deep test: [default-tier tests]} from the table under the '## The deep tier' heading."""
    text = doc.read_text()
    section = text.split("## The deep tier", 1)
    if len(section) < 2:
        return None
    rows = {}
    for line in section[1].split("\n## ", 1)[0].splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 3 or not line.lstrip().startswith("|") or set(cells[0]) <= set("-: "):
            continue
        first = NAME.findall(cells[0])
        if len(first) == 1:
            rows[first[0]] = NAME.findall(cells[-1])
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", type=pathlib.Path, required=True, help="a configured build folder")
    ap.add_argument("--doc", type=pathlib.Path, default=pathlib.Path(__file__).resolve().parent.parent / "docs" / "testing.md")
    ap.add_argument("--ctest", default=shutil.which("ctest") or "ctest")
    a = ap.parse_args()
    if not (a.build / "CTestTestfile.cmake").is_file():
        print(f"check_tiers.py: {a.build} is no configured build folder (no CTestTestfile.cmake)")
        return 4
    rows = deep_table(a.doc) if a.doc.is_file() else None
    if rows is None:
        print(f"check_tiers.py: {a.doc}: no '## The deep tier' section with a table")
        return 4
    labels = read_labels(a.build, a.ctest)
    deep = {t for t, ls in labels.items() if "deep" in ls}
    problems = [f"{a.doc.name}: deep test {t} has no row saying where the default tier runs its check" for t in sorted(deep - set(rows))]
    for t, default in sorted(rows.items()):
        if t not in labels:
            problems.append(f"{a.doc.name}: row {t}: no such test")
        elif t not in deep:
            problems.append(f"{a.doc.name}: row {t}: the test is in the default tier (no 'deep' label)")
        if not default:
            problems.append(f"{a.doc.name}: row {t}: names no default-tier test that runs its check")
        for d in default:
            if d not in labels:
                problems.append(f"{a.doc.name}: row {t}: {d}: no such test")
            elif d in deep:
                problems.append(f"{a.doc.name}: row {t}: {d} is deep too: the check must run in the default tier")
    for p in problems:
        print(p)
    if not problems:
        print(f"{len(deep)} deep tests, each repeating a check the default tier runs")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
