#!/usr/bin/env python3
"""scripts/test_times.py — where the test command's time goes, from CTest's own record.

  scripts/test_times.py [--build build/release] [--by avg|last] [--top 30] [--markdown]

Prints every test's time, the slowest (--top, 30 by default) and the sum per label. Nothing is
run and nothing is timed here: the times are the ones CTest itself wrote in the build folder,
  Testing/Temporary/CTestCostData.txt   "name runs cost" per test: CTest's running average of
                                        the test's time over its passing runs in this build
                                        folder (what it schedules -j by; "0 0" for a test that
                                        has not passed yet), then a '---' line and the names
                                        of the tests that last failed;
  Testing/Temporary/LastTest.log        "Test time = S sec" after each test of the latest ctest
                                        invocation only (one run of each; a subset after -R or -L).
--by avg (the default) sorts and sums the averages; --by last the latest invocation's times. The
labels come from CTest's listing, `ctest --show-only=json-v1`, of the build folder's tests (each
test's LABELS property; listed from a scratch folder, so the build folder is not written); a test
with several labels counts in each, so the label sums overlap and add up to more than the total.

A figure is only as quiet as the run that made it: under `ctest -j2` each test shares the machine
with one other, and a run beside other work is slower. Say which run the figures come from.
"""

import argparse
import json
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import tempfile

# LastTest.log: "12/1941 Test: conformance.goldens" opens a test's block, "Test time =   1.23 sec"
# follows its output. A test repeated after a timeout appears twice; the last block wins, as in
# CTest's own summary.
_LOG_TEST = re.compile(r"^\s*\d+/\d+ Test: (.+?)\s*$")
_LOG_TIME = re.compile(r"^Test time =\s*([0-9.]+)\s*sec")


def read_cost_data(path):
    """{name: (runs, average seconds)} and the set of tests CTest lists as failed last."""
    costs, failed, in_failed = {}, set(), False
    for n, line in enumerate(path.read_text().splitlines(), 1):
        line = line.strip()
        if not line:
            continue
        if line == "---":
            in_failed = True
            continue
        if in_failed:
            failed.add(line)
            continue
        # rsplit: the name is everything before the last two fields.
        parts = line.rsplit(" ", 2)
        try:
            runs, cost = int(parts[1]), float(parts[2])
        except (IndexError, ValueError):
            sys.exit(f"{path}:{n}: not a 'name runs cost' line: {line!r}")
        # CTest lists every registered test, "0 0" until a run of it passes: not a time.
        if runs > 0:
            costs[parts[0]] = (runs, cost)
    return costs, failed


def read_last_log(path):
    """{name: seconds} of the latest ctest invocation."""
    times, current = {}, None
    for line in path.read_text(errors="replace").splitlines():
        m = _LOG_TEST.match(line)
        if m:
            current = m.group(1)
            continue
        m = _LOG_TIME.match(line)
        if m and current is not None:
            times[current] = float(m.group(1))
            current = None
    return times


def read_labels(build, ctest):
    """{name: [labels]} from CTest's own listing of the build folder's tests.

    `ctest --show-only` starts a new Testing/Temporary/LastTest.log in the folder it lists (CMake 3.25
    empties it), which would wipe the record this script reads, or cut into a test run going on in
    that folder. So the listing runs from a scratch folder whose only test file includes the build's
    (`subdirs`): the same tests and properties, and the build folder is not written."""
    with tempfile.TemporaryDirectory(prefix="test_times.") as scratch:
        top = pathlib.Path(scratch) / "CTestTestfile.cmake"
        top.write_text(f'subdirs("{build.resolve().as_posix()}")\n')
        try:
            out = subprocess.run([ctest, "--test-dir", scratch, "--show-only=json-v1"], check=True,
                                 capture_output=True, text=True).stdout
        except (OSError, subprocess.CalledProcessError) as e:
            detail = getattr(e, "stderr", "") or str(e)
            sys.exit(f"test_times.py: listing the tests of {build} with `{ctest} --show-only=json-v1` failed: {detail.strip()}")
    labels = {}
    for t in json.loads(out).get("tests", []):
        props = {p["name"]: p["value"] for p in t.get("properties", [])}
        value = props.get("LABELS", [])
        labels[t["name"]] = [value] if isinstance(value, str) else list(value)
    return labels


# A text table's cells are cut to this width (GoogleTest's parameterised names run to 200 characters);
# --markdown keeps them whole.
_TEXT_CELL = 90


def fmt_s(x):
    return "—" if x is None else f"{x:.2f}"


def table(headers, rows, markdown):
    """Rows of strings as a Markdown table or as aligned columns (numbers right-aligned)."""
    if markdown:
        out = ["| " + " | ".join(headers) + " |", "|" + "|".join(" --- " for _ in headers) + "|"]
        out += ["| " + " | ".join(c.replace("|", "\\|") for c in r) + " |" for r in rows]
        return "\n".join(out)
    rows = [[c if len(c) <= _TEXT_CELL else c[: _TEXT_CELL - 1] + "…" for c in r] for r in rows]
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h) for i, h in enumerate(headers)]
    numeric = [all(re.fullmatch(r"[0-9.,% —]+", r[i]) for r in rows) if rows else False for i in range(len(headers))]

    def line(cells):
        return "  ".join(c.rjust(w) if num else c.ljust(w) for c, w, num in zip(cells, widths, numeric)).rstrip()

    return "\n".join([line(headers), line(["-" * w for w in widths])] + [line(r) for r in rows])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", type=pathlib.Path, default=pathlib.Path("build/release"),
                    help="the CTest build folder (default: build/release)")
    ap.add_argument("--by", choices=["avg", "last"], default=None,
                    help="avg: CTestCostData.txt's running averages (the default when it exists); "
                         "last: LastTest.log's times of the latest ctest invocation")
    ap.add_argument("--top", type=int, default=30, help="how many of the slowest tests to list (default 30)")
    ap.add_argument("--markdown", action="store_true", help="Markdown tables, to paste into a README")
    ap.add_argument("--ctest", default=shutil.which("ctest") or "ctest", help="the ctest executable")
    a = ap.parse_args()

    build = a.build
    if not (build / "CTestTestfile.cmake").is_file():
        sys.exit(f"test_times.py: {build} is not a CTest build folder (no CTestTestfile.cmake); "
                 "configure and build first (README.md, Quick start), or pass --build DIR")
    temp = build / "Testing" / "Temporary"
    cost_file, log_file = temp / "CTestCostData.txt", temp / "LastTest.log"
    have_cost, have_log = cost_file.is_file(), log_file.is_file()
    if not have_cost and not have_log:
        sys.exit(f"test_times.py: {build} has no test record ({cost_file} and {log_file} are missing): "
                 f"run the tests first (`ctest --preset release`, or `ctest --test-dir {build}`)")
    by = a.by or ("avg" if have_cost else "last")
    if by == "avg" and not have_cost:
        sys.exit(f"test_times.py: --by avg needs {cost_file}, which is missing (try --by last)")
    if by == "last" and not have_log:
        sys.exit(f"test_times.py: --by last needs {log_file}, which is missing (try --by avg)")

    costs, failed = read_cost_data(cost_file) if have_cost else ({}, set())
    last = read_last_log(log_file) if have_log else {}
    if by == "avg" and not costs:
        sys.exit(f"test_times.py: {cost_file} holds no time: no test has passed in {build} yet "
                 "(every line '0 0'); run the tests, or use --by last")
    if by == "last" and not last:
        sys.exit(f"test_times.py: {log_file} holds no test time: its latest ctest invocation ran no test "
                 "(--show-only, or a -R that matched nothing); run the tests, or use --by avg")
    labels = read_labels(build, a.ctest)

    # Every test CTest has registered, and any the record still holds that is no longer registered
    # (renamed or removed since: marked, and left out of the label sums).
    names = sorted(set(labels) | set(costs) | set(last))
    key = {n: (costs[n][1] if n in costs else None) if by == "avg" else last.get(n) for n in names}
    timed = [n for n in names if key[n] is not None]
    total = sum(key[n] for n in timed)

    def row(n):
        runs = str(costs[n][0]) if n in costs else "—"
        avg = fmt_s(costs[n][1]) if n in costs else "—"
        note = ("" if n in labels else "not registered now") + (" failed last" if n in failed else "")
        return [n, avg, runs, fmt_s(last.get(n)), ",".join(labels.get(n, [])), note.strip()]

    headers = ["test", "avg s", "runs", "last s", "labels", "note"]
    source = {"avg": f"{cost_file} (running average over runs)", "last": f"{log_file} (latest invocation)"}[by]
    print(f"# Every test, by name ({len(names)} tests, {len(timed)} timed; sorted and summed by {by}: {source})\n")
    print(table(headers, [row(n) for n in names], a.markdown))

    slowest = sorted(timed, key=lambda n: -key[n])[: a.top]
    print(f"\n# The {len(slowest)} slowest, by {by}\n")
    print(table(["#"] + headers[:5] + ["% of all"],
                [[str(i + 1)] + row(n)[:5] + [f"{100 * key[n] / total:.1f}" if total else "—"]
                 for i, n in enumerate(slowest)], a.markdown))

    per = {}
    for n in timed:
        if n not in labels:
            continue
        for lab in labels[n] or ["(no label)"]:
            s = per.setdefault(lab, [0, 0.0, 0.0, ""])
            s[0] += 1
            s[1] += key[n]
            if key[n] > s[2]:
                s[2], s[3] = key[n], n
    print(f"\n# Sum per label, by {by} (a test counts in each of its labels)\n")
    print(table(["label", "tests", "sum s", "% of all", "slowest", "its s"],
                [[lab, str(c), f"{s:.1f}", f"{100 * s / total:.1f}" if total else "—", top, f"{mx:.2f}"]
                 for lab, (c, s, mx, top) in sorted(per.items(), key=lambda kv: -kv[1][1])], a.markdown))

    untimed = [n for n in names if key[n] is None and n in labels]
    print(f"\nAll {len(timed)} timed tests: {total:.1f} s summed ({total / 60:.1f} min; under -jN the wall "
          f"time is about the sum over N when no one test dominates)."
          + (f" {len(untimed)} registered tests have no {by} time." if untimed else ""))
    return 0


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `| head` ends the output quietly
    sys.exit(main())
