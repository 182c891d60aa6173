#!/usr/bin/env python3
"""SIGTERM in each stage of a `shadowref conform` run ends it within 2 s of the signal, one CTest
test per stage (docs/output-contract.md, "What you can rely on after a crash"):

  references    a cold cache, the large level at 4 x its resolution: the signal once the run is
                computing its reference (Embree and TBB threads, about 5 s of tiles)
  drawing       the level at 2 x, PCSS: the signal once it is drawing (one light's pass alone
                rasterises for seconds on llvmpipe)
  judging       the level at 2 x, a shadow map: the signal once it is judging (the causes of its
                wrong pixels, the resolving power's probes)
  error-images  a small run; the signal in the first write of an error image
  report        a small run; the signal in the first write into the staged report folder

Each run exits 143 (128 + SIGTERM) within 2 s of the signal, measured from the signal, with the
interruption line last on stderr; it leaves no report.json, no hidden partial name and, for the
references, no cache entry of the scene it was computing.

How a stage is known to be reached, never by a time: the first three watch the run's stall lines,
which name the step the run is in ("still judging level x shadowmap ..."), with their interval
shortened to 100 ms (SHADOWREF_STALL_REPORT_MS, a test hook); each stage then lasts seconds, so the
signal lands inside it. The writes are too short for that: the fault shim (faults/fault_shim.cpp)
raises the signal in the counted write and says so on stderr, and the 2 s are timed from that line.

Under a sanitizer (--sanitized: the asan and tsan presets) the run is the same and so are its
checks, but two things differ from a release build, and the test allows for each: LeakSanitizer
scans the heap after the interruption line (seconds on a run that loaded Mesa and Embree), so the
time is taken from the signal to that line, not to the exit; and the instrumented code runs two to
three times slower between the run's checks, so the limit is SANITIZED_LIMIT_S. ASan refuses a
preloaded library ahead of its runtime unless told the order is intended (verify_asan_link_order=0),
as faults_test.cpp tells it.

usage: interrupt_test.py --shadowref EXE --shim LIB --catalogue DIR --work DIR [--sanitized] STAGE
"""
import argparse
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import threading
import time

LIMIT_S = 2.0        # from the signal to the process's exit
# Under ASan + UBSan or TSan: the checks' spacing (about 0.5 s of work in a release build) grows by
# the instrumentation's slowdown, two to three times, and a sanitized suite runs its tests two at a
# time on two cores (the level's interrupted reference was told 6.25 s after the signal so,
# 2026-12-02); timed to the interruption line.
SANITIZED_LIMIT_S = 6 * LIMIT_S
INTERRUPTED = "shadowref conform: interrupted by SIGTERM"
REACH_TIMEOUT_S = 300  # a hang guard for reaching the stage, not a timing check

LEVEL = ["--scenes", "level", "--spp", "1", "--jobs", "2"]
SMALL = ["--scenes", "ground_sphere", "--techniques", "shadowmap", "--resolution", "64x64", "--jobs", "1"]

# stage: (conform arguments, the stderr line that says the stage is reached, what the shim counts)
STAGES = {
    "references": (LEVEL + ["--techniques", "shadowmap", "--resolution-scale", "4"],
                   r"still computing the reference of level after", None),
    "drawing": (LEVEL + ["--techniques", "pcss", "--resolution-scale", "2"], r"still drawing level x pcss after", None),
    "judging": (LEVEL + ["--techniques", "shadowmap", "--resolution-scale", "2"], r"still judging level x shadowmap", None),
    "error-images": (SMALL, r"^fault shim: raising signal", "renders/ground_sphere/shadowmap/.error"),
    "report": (SMALL, r"^fault shim: raising signal", ".report.partial"),
}


class Stderr:
    """The child's stderr, read on a thread of its own; `reached` is set at the first line matching."""

    def __init__(self, stream, pattern):
        self.lines = []
        self.reached = threading.Event()
        self.interrupted_at = None  # time.monotonic() when the interruption line was read
        self.pattern = re.compile(pattern)
        self.thread = threading.Thread(target=self.read, args=(stream,), daemon=True)
        self.thread.start()

    def read(self, stream):
        for line in stream:
            self.lines.append(line.rstrip("\n"))
            if self.interrupted_at is None and line.startswith(INTERRUPTED):
                self.interrupted_at = time.monotonic()
            if self.pattern.search(line):
                self.reached.set()

    def text(self):
        return "\n".join(self.lines)


def partial_names(folder):
    return [str(p) for p in folder.rglob("*") if ".partial-" in p.name]


def run_stage(args, stage):
    conform_args, pattern, shim_under = STAGES[stage]
    work = pathlib.Path(os.path.realpath(args.work))  # the shim compares real paths
    shutil.rmtree(work, ignore_errors=True)
    out = work / "out"
    cmd = [args.shadowref, "conform", "--catalogue", args.catalogue, "--out", str(out)] + conform_args
    env = dict(os.environ, SHADOWREF_STALL_REPORT_MS="100", MESA_SHADER_CACHE_DISABLE="true")
    if shim_under:
        env.update(LD_PRELOAD=args.shim, SHADOWREF_FAULT_UNDER=str(out / shim_under), SHADOWREF_FAULT_IN_WRITE="1",
                   SHADOWREF_FAULT_SIGNAL=str(int(signal.SIGTERM)), SHADOWREF_FAULT_SAY="1")
        if args.sanitized:
            env["ASAN_OPTIONS"] = env.get("ASAN_OPTIONS", "") + ":verify_asan_link_order=0"
    child = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, errors="replace", env=env)
    err = Stderr(child.stderr, pattern)
    start = time.monotonic()
    while not err.reached.wait(0.05):
        if child.poll() is not None or time.monotonic() - start > REACH_TIMEOUT_S:
            child.kill()
            child.wait()
            err.thread.join()
            return [f"the run never reached the stage (no line matching {pattern!r}; exit {child.returncode}):\n{err.text()}"]
    signalled = time.monotonic()
    if not shim_under:
        child.send_signal(signal.SIGTERM)
    try:
        code = child.wait(timeout=REACH_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        child.kill()
        code = child.wait()
    exited = time.monotonic()
    err.thread.join()
    print(f"{stage}: stage reached {signalled - start:.2f} s after the start; exit {code} {exited - signalled:.2f} s after SIGTERM")
    problems = []
    if code != 128 + signal.SIGTERM:
        problems.append(f"exit {code}, not {128 + signal.SIGTERM} (interrupted by SIGTERM)")
    if args.sanitized:
        if err.interrupted_at is None:
            problems.append("no interruption line on stderr")
        elif err.interrupted_at - signalled > SANITIZED_LIMIT_S:
            problems.append(f"said it was interrupted {err.interrupted_at - signalled:.2f} s after SIGTERM: "
                            f"more than {SANITIZED_LIMIT_S} s (sanitized build)")
    elif exited - signalled > LIMIT_S:
        problems.append(f"exited {exited - signalled:.2f} s after SIGTERM: more than {LIMIT_S} s")
    last = err.lines[-1] if err.lines else ""
    if not last.startswith(INTERRUPTED):
        problems.append(f"the last stderr line is not the interruption's: {last!r}")
    if (out / "report.json").exists():
        problems.append("a report.json was left: it says the run finished")
    problems += [f"a partial name was left: {p}" for p in partial_names(work)]
    cache = out / "reference-cache"
    if stage == "references" and cache.is_dir():
        problems += [f"a cache entry of the interrupted reference was published: {e}" for e in cache.glob("level-*")]
    if problems:
        problems.append("stderr:\n" + err.text())
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--shadowref", required=True)
    parser.add_argument("--shim", required=True)
    parser.add_argument("--catalogue", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--sanitized", action="store_true",
                        help="the build is instrumented (ASan + UBSan or TSan): see above")
    parser.add_argument("stage", choices=sorted(STAGES))
    args = parser.parse_args()
    problems = run_stage(args, args.stage)
    for p in problems:
        print("FAIL:", p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
