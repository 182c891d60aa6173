#!/usr/bin/python3
"""track_test.py — the tracker's regression verdicts on recorded runs made up for the purpose.

`bench/track --compare OLD NEW` judges same-run ratios (ours against its peer) and must neither cry
wolf nor sleep through a regression:
  - the same code on a machine twice as slow (every time doubled): 0 regressions, exit 0 — the first
    version of the tool, comparing absolute times, reported regressions here;
  - ours 30 % slower, its peer unchanged: a regression, exit 1, naming the case;
  - ours 5 % slower: within the 15 % threshold, exit 0;
  - ours 20 % slower in runs whose repetitions spread by 40 %: within the spread, exit 0;
  - the same 20 % with tight repetitions: a regression, exit 1;
  - a ceiling measured two ways (two copy loops) whose slower way gets twice as fast, as code
    placement alone can make it, ours and the faster way unchanged: exit 0 (the ceiling is the
    faster of the two in each run).
Runs nothing but the tracker's comparison (no benchmark binary); a few seconds.
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

TRACK = Path(__file__).resolve().parent / "track"
OURS, PEER = "BM_PointBatch_Ours/points:1000", "BM_PointBatch_Eigen/points:1000"
COPY, COPY4 = "BM_PointBatch_Stream/points:1000", "BM_PointBatch_StreamUnrolled/points:1000"


def run_json(times, spread=0.0):
    """Google Benchmark JSON with 9 repetitions per benchmark around the given median (ms), spread
    evenly over ±spread/2 of it, and the median aggregate."""
    benchmarks = []
    for name, ms in times.items():
        for k in range(9):
            t = ms * (1 + spread * (k - 4) / 8)
            benchmarks.append({"name": name, "run_name": name, "run_type": "iteration", "repetitions": 9,
                               "repetition_index": k, "real_time": t, "cpu_time": t, "time_unit": "ms"})
        benchmarks.append({"name": name + "_median", "run_name": name, "run_type": "aggregate",
                           "aggregate_name": "median", "real_time": ms, "cpu_time": ms, "time_unit": "ms"})
    return {"context": {"date": "2026-11-22"}, "benchmarks": benchmarks}


def verdict(old, new, old_spread=0.0, new_spread=0.0):
    with tempfile.TemporaryDirectory() as d:
        for name, times, spread in (("old", old, old_spread), ("new", new, new_spread)):
            (Path(d) / name).mkdir()
            (Path(d) / name / "math.json").write_text(json.dumps(run_json(times, spread)))
        p = subprocess.run([sys.executable, str(TRACK), "--compare", str(Path(d) / "old"), str(Path(d) / "new")],
                           capture_output=True, text=True)
        return p.returncode, p.stdout


def main():
    base = {OURS: 1.0, PEER: 2.5}
    failures = []

    def expect(what, got, code, needle=None):
        rc, out = got
        if rc != code or (needle and needle not in out):
            failures.append(f"{what}: exit {rc} (expected {code}){'' if not needle else f', {needle!r} in output: {needle in out}'}")

    expect("machine twice as slow", verdict(base, {k: 2 * v for k, v in base.items()}), 0)
    expect("ours 30 % slower", verdict(base, {OURS: 1.3, PEER: 2.5}), 1, "N=1000 ours vs Eigen's product")
    expect("ours 5 % slower", verdict(base, {OURS: 1.05, PEER: 2.5}), 0)
    expect("ours 20 % slower, spread 40 %", verdict(base, {OURS: 1.2, PEER: 2.5}, 0.4, 0.4), 0)
    expect("ours 20 % slower, tight", verdict(base, {OURS: 1.2, PEER: 2.5}), 1)
    copies = {OURS: 1.0, PEER: 2.5, COPY: 0.8, COPY4: 0.4}
    expect("the slower copy twice as fast", verdict(copies, {**copies, COPY: 0.4}), 0)
    expect("ours 30 % slower against the copies", verdict(copies, {**copies, OURS: 1.3}), 1, "ours vs streaming ceiling")
    for f in failures:
        print("FAIL:", f)
    print(f"track_test: {7 - len(failures)} of 7 verdicts as expected")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
