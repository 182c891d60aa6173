#!/usr/bin/env python3
"""`shadowref conform --no-resolving-power` judges as the plain run does: the same report.json but
for the resolving power (scripts/same_report.py, every key but times and paths), which it leaves
out, and says so in one line. The sweeps rely on it (conformance/tests/CMakeLists.txt).

    no_resolving_power_test.py --shadowref EXE --scene SCENE_FILE --cache DIR --work DIR
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
SAME_REPORT = HERE.parents[1] / "scripts" / "same_report.py"
# A hard map, a filtered one (the cause model's texel questions) and a soft one (the lit fraction):
# each judges through a different part of the comparison.
TECHNIQUES = "shadowmap,shadowmap-pcf,pcss"


def conform(a, out, *extra):
    cmd = [str(a.shadowref), "conform", "--scenes", str(a.scene), "--techniques", TECHNIQUES, "--cache", str(a.cache),
           "--out", str(out), "--jobs", "1", *extra]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode not in (0, 1):
        sys.exit(f"{' '.join(cmd)}: exit {p.returncode}\n{p.stdout}")
    return p.returncode, p.stdout, json.loads((out / "report.json").read_text())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shadowref", required=True, type=pathlib.Path)
    ap.add_argument("--scene", required=True, type=pathlib.Path)
    ap.add_argument("--cache", required=True, type=pathlib.Path)
    ap.add_argument("--work", required=True, type=pathlib.Path)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    a.work.mkdir(parents=True)
    with_rp, without_rp = a.work / "probed", a.work / "not-probed"
    code_a, out_a, report_a = conform(a, with_rp)
    code_b, out_b, report_b = conform(a, without_rp, "--no-resolving-power")
    failures = []
    if code_a != code_b:
        failures.append(f"exit {code_a} with the probes, {code_b} without")
    probed = [c["scene"] + "/" + c["technique"] for c in report_a["cases"] if "resolving_power" in c]
    if len(probed) != len(report_a["cases"]) or not probed:
        failures.append(f"the plain run has a resolving power for {len(probed)} of {len(report_a['cases'])} cases")
    left = [c["scene"] + "/" + c["technique"] for c in report_b["cases"] if "resolving_power" in c]
    if left:
        failures.append(f"--no-resolving-power still wrote a resolving power for {', '.join(left)}")
    if "resolving power: not computed (--no-resolving-power)" not in out_b:
        failures.append("--no-resolving-power's run does not say that it computed no resolving power:\n" + out_b)
    # Everything else the same: verdicts, metrics, causes, statuses.
    same = subprocess.run([sys.executable, str(SAME_REPORT), "--ignore", "resolving_power",
                           str(with_rp / "report.json"), str(without_rp / "report.json")],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if same.returncode != 0:
        failures.append("the two reports differ beyond the resolving power:\n" + same.stdout)
    if failures:
        print("\n".join(failures))
        return 1
    print(f"{len(report_a['cases'])} cases judged alike with and without the resolving power's probes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
