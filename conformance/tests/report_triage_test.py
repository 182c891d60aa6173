#!/usr/bin/env python3
"""Triage in the report page, end to end (docs/ci.md, "Triage in the report"): a person marks
failures known in the HTML report and the file the page downloads makes the next run green.

Our own shadowmap renders of three scenes are the candidate, two of them with the mask inverted
(two FAILs; the third PASSes). The team's file holds a line of another convention and a [skips]
regex (kept, as expectations-update.txt keeps them; a comment line alone is not). Judged with it: exit 2, two new failures. In headless Chromium, by clicking (triage_click.mjs):
  one case marked: the downloaded file keeps the team's lines, adds that case's line with its bug
                   link, and the next run still exits 2 (the unmarked case stays new);
  both marked:     the next run with the downloaded file exits 0, both cases known failures.

usage: report_triage_test.py --shadowref EXE --cache DIR --work DIR --node EXE --chromium EXE --web DIR
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts"))
from png8 import read_png, write_png  # noqa: E402 (the project's scripts folder)

SCENES = ["directional_light", "ground_sphere", "shadow_on_object"]
BROKEN = {"directional_light": "https://bugs.example/101", "ground_sphere": "https://bugs.example/102#c3"}
GIVEN = ("# the team's file\nshadow_on_object@shadowmap@d3d,FAIL  # another convention's line, kept (a </script><!-- in it)\n"
         "[skips]\n^no_such_scene@\n")


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


def run(cmd, expect):
    p = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=600)
    if p.returncode != expect:
        fail(f"{' '.join(map(str, cmd))}: exit {p.returncode}, expected {expect}\n{p.stdout}\n{p.stderr}")
    return p


def main():
    ap = argparse.ArgumentParser()
    for k in ("shadowref", "cache", "work", "node", "chromium", "web"):
        ap.add_argument(f"--{k}", required=True, type=pathlib.Path)
    a = ap.parse_args()
    work = a.work.resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    common = ["--scenes", ",".join(SCENES), "--cache", a.cache, "--jobs", "1", "--quiet", "--no-resolving-power"]
    run([a.shadowref, "conform", *common, "--techniques", "shadowmap", "--out", work / "ours"], expect=0)
    candidates = work / "candidates"
    for scene in SCENES:
        (candidates / scene).mkdir(parents=True)
        mask = candidates / scene / "mask.png"
        shutil.copy(work / "ours" / "renders" / scene / "shadowmap" / "mask.png", mask)
        if scene in BROKEN:
            w, h, rows = read_png(mask)
            write_png(mask, w, h, [bytearray(255 - v if v in (0, 255) else v for v in r) for r in rows])
    given = work / "given.txt"
    given.write_text(GIVEN)

    def judge(out, expect, expectations):
        return run([a.shadowref, "conform", *common, "--candidate-dir", candidates, "--technique", "shadowmap", "--out",
                    work / out, "--expectations", expectations], expect=expect)

    judge("run", 2, given)
    triage = json.loads((work / "run" / "report.json").read_text())["triage"]
    if sorted(c["scene"] for c in triage["cases"]) != sorted(BROKEN):
        fail(f"report.json's triage names {triage['cases']}, not the two broken scenes")

    def click(name, marks):
        cmd = [a.node, pathlib.Path(__file__).with_name("triage_click.mjs"), "--page", work / "run" / "report" / "index.html",
               "--download", work / name, "--web", a.web, "--chromium", a.chromium]
        for scene in marks:
            cmd += ["--mark", f"{scene}@shadowmap={BROKEN[scene]}"]
        p = run(cmd, expect=0)
        if p.stdout.strip() != f"{len(marks)} of {len(BROKEN)} marked":
            fail(f"the page counts '{p.stdout.strip()}' after marking {marks}")
        text = (work / name / "expectations.txt").read_text()
        for line in GIVEN.splitlines()[1:]:  # a comment line alone is not kept (as in expectations-update.txt)
            if line not in text.splitlines():
                fail(f"the downloaded file lost the given line '{line}':\n{text}")
        for scene in BROKEN:
            wanted = f"{scene}@shadowmap@gl,FAIL  # {BROKEN[scene]} (marked in the report)"
            if (wanted in text.splitlines()) != (scene in marks):
                fail(f"'{wanted}' {'missing from' if scene in marks else 'in'} the downloaded file:\n{text}")
        if text.index("[skips]") < text.index(f"{marks[0]}@shadowmap@gl,FAIL"):
            fail(f"a marked line after the [skips] header, where it would be read as a regex:\n{text}")
        return work / name / "expectations.txt"

    one = click("one-marked", ["directional_light"])
    p = judge("after-one", 2, one)
    if "NEW FAILURE ground_sphere@shadowmap" not in p.stdout:
        fail(f"the unmarked case is not a new failure:\n{p.stdout}")
    both = click("both-marked", list(BROKEN))
    p = judge("after-both", 0, both)
    counts = json.loads((work / "after-both" / "report.json").read_text())["expectations"]["counts"]
    if counts.get("expected") != 2 or counts.get("new-failure") != 0:
        fail(f"the marked cases are not the known failures of the next run: {counts}")
    print("report triage: 2 cases marked in the page; the downloaded file keeps the given lines and the next run exits 0")


if __name__ == "__main__":
    main()
