#!/usr/bin/python3
"""engines/run_engines.py — judge the real engines and hold their verdicts to the recorded table.

Exports the pack with the built `shadowref`, renders it with each run of engines/verdicts.json (a
harness and its variant: the C++ harnesses under a virtual X display, the web ones — three.js and
Babylon.js, engines/web/ — with Node in headless Chromium), lets `shadowref conform --candidate-dir` judge
each candidate folder, and compares every scene's verdict with the one recorded. Any difference — a
verdict that changed, a scene added or lost — fails, with the report to look at.

  run_engines.py --shadowref EXE --irrlicht EXE --osg EXE --work DIR [--verdicts FILE] [--runs GLOB,..] [--record]

--runs renders and judges only the runs whose names match (for working on one harness); the test
runs them all. The web runs of one engine and backend are rendered first, together, in one browser
(render.mjs --batch): each run's line then gives its judging time, a native run's its rendering and
judging.

Scenes in verdicts.json's `not_judged` are rendered by the harnesses that render every scene but not
judged on the harnesses each entry names: those harnesses cannot yet give their engine what the scenes
need (the entry's `why` says what).

A run with a `twin` (a WebGPU run beside the WebGL2 run of the same engine and variant) is compared
with it when both are rendered: per scene, how many mask pixels the two backends' masks differ in,
beside each one's verdict (printed, and written to <work>/backends.md), and `shadowref diff` of the
two judged runs writes the side-by-side page <work>/backends/<run>-vs-<twin>/diff.html, which
backends.md links.

--record rewrites the verdicts of verdicts.json from this run, keeping each *why* and *cause* whose
verdict did not change and emptying the others (engines/readme_table.py then refuses a non-PASS
without them until someone has looked at the report and written them).
"""

import argparse
import fnmatch
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time
import zlib

# report.json is read as the record library reads it: held to its schema first.
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "conformance" / "record"))
import report_record  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
# Irrlicht needs an X display with a stencil buffer; Mesa's llvmpipe draws through Xvfb's GLX.
# -noreset: an X server resets when its last client leaves, and a harness that opens a new device per
# scene then races the reset ("Could not open display" on a random scene).
XVFB_ARGS = "-screen 0 1024x1024x24 -noreset"


def run(cmd, **kwargs):
    return subprocess.run([str(c) for c in cmd], **kwargs)


def under_xvfb(cmd, work):
    # xvfb-run -a finds a free display itself; its authority file goes in our work folder rather than
    # a temporary folder under /tmp, which other jobs on a shared machine have been seen to clean up
    # mid-run (new connections then fail).
    return ["xvfb-run", "-a", "-f", work / "Xauthority", "-s", XVFB_ARGS] + cmd


WEB = HERE / "web"
WEB_HARNESSES = ("three", "babylon")


def web_ready():
    """None when the web harnesses can run, else what is missing (scripts/setup.sh provides both)."""
    if shutil.which("node") is None:
        return "node (Debian package nodejs)"
    if not (WEB / "node_modules" / ".package-lock.json").exists():
        return f"{WEB / 'node_modules'} (npm ci in {WEB}, which scripts/setup.sh runs)"
    return None


def web_batches(runs):
    """The web runs in groups of one engine and backend, in the table's order: each group is rendered
    by one render.mjs --batch, one browser for all its variants (what it shares is the browser's
    start and the engine's loading; every folder is what its variant alone renders)."""
    groups = {}
    for r in runs:
        if r["harness"] in WEB_HARNESSES:
            groups.setdefault((r["harness"], r.get("backend", "webgl2")), []).append(r)
    return list(groups.items())


def render_web_batch(engine, backend, runs, pack, work):
    jobs = [{"variant": r["variant"], "out": str(work / "renders" / r["run"]),
             # a run of the scenes its engine can light so (engines/README.md says why)
             **({"scenes": r["scenes"]} if r.get("scenes") else {})} for r in runs]
    batch = work / f"batch-{engine}-{backend}.json"
    batch.write_text(json.dumps(jobs, indent=1) + "\n")
    # webgl2 (the default), webgpu, webgpu-webgl2: render.mjs refuses any other backend it finds
    cmd = ["node", WEB / "render.mjs", "--engine", engine, "--pack", pack, "--batch", batch, "--backend", backend]
    p = run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        sys.exit(f"{', '.join(r['run'] for r in runs)}: the {engine} harness ({backend}) failed (exit {p.returncode}):\n{p.stdout}")


def render(r, exes, pack, out, work):
    """A native harness's render of one run (the web runs are rendered in batches: render_web_batch)."""
    cmd = under_xvfb([exes[r["harness"]], "--pack", pack, "--out", out, "--variant", r["variant"]], work)
    # The native harnesses draw with Mesa's llvmpipe, in the calling thread as our renderer does: its
    # rasteriser threads can free a fence under the thread that signals it (docs/architecture.md,
    # "The GL context"). Every recorded engine verdict is the same either way (engines.verdicts).
    env = dict(os.environ, LP_NUM_THREADS="0")
    p = run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    if p.returncode != 0:
        sys.exit(f"{r['run']}: the harness failed (exit {p.returncode}):\n{p.stdout}")


def not_judged_on(table, harness):
    """The scenes verdicts.json's not_judged keeps from `harness`'s runs: each entry names the
    harnesses that cannot render its scenes faithfully yet, and why."""
    return {s for entry in table.get("not_judged", []) if harness in entry["harnesses"] for s in entry["scenes"]}


def judged_scenes(r, pack, not_judged):
    """The scenes a run is judged on: its own list, or every scene of the pack but those its harness
    does not render faithfully yet (not_judged_on)."""
    if r.get("scenes"):
        return r["scenes"]
    return [f.stem for f in sorted((pack / "scenes").glob("*.json")) if f.stem not in not_judged]


def judge(r, shadowref, pack, candidates, out, cache, scenes, probe):
    """Each scene's status. `probe`: with each case's resolving power, which only a person reads (a
    recording, whose non-PASS verdicts get their why from the reports); the verdicts are the same
    without it (conformance.no_resolving_power), and a check of them needs none."""
    cmd = [shadowref, "conform", "--catalogue", pack / "scenes", "--candidate-dir", candidates,
           "--technique", r["technique"], "--out", out, "--cache", cache, "--quiet", "--scenes", ",".join(scenes)]
    if not probe:
        cmd.append("--no-resolving-power")
    p = run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode not in (0, 1, 2):  # 0 pass, 1 warnings, 2 failures: all verdicts; others are errors
        sys.exit(f"{r['run']}: shadowref conform failed (exit {p.returncode}):\n{p.stdout}")
    try:
        return report_record.case_statuses(report_record.read_report(out / "report.json"))
    except report_record.ReportError as e:
        sys.exit(f"{r['run']}: {e}")


def grey_png(path):
    """An 8-bit greyscale PNG (the masks every harness writes) as (width, height, bytes): zlib and the
    five row filters of the PNG specification, nothing else (no third-party module)."""
    data = path.read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat, width = 8, b"", None
    while pos < len(data):
        n = int.from_bytes(data[pos:pos + 4], "big")
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            width, height = int.from_bytes(body[0:4], "big"), int.from_bytes(body[4:8], "big")
            if body[8] != 8 or body[9] != 0 or body[12] != 0:
                raise ValueError(f"{path}: not 8-bit greyscale without interlace")
        elif kind == b"IDAT":
            idat += body
    raw, out, prev = zlib.decompress(idat), bytearray(), bytearray(width)
    for y in range(height):
        f, row = raw[y * (width + 1)], bytearray(raw[y * (width + 1) + 1:(y + 1) * (width + 1)])
        for x in range(width if f else 0):
            a = row[x - 1] if x else 0
            b, c = prev[x], (prev[x - 1] if x else 0)
            if f == 1:
                row[x] = (row[x] + a) & 255
            elif f == 2:
                row[x] = (row[x] + b) & 255
            elif f == 3:
                row[x] = (row[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[x] = (row[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += row
        prev = row
    return width, height, bytes(out)


def mask_difference(a_dir, b_dir):
    """(pixels that differ, pixels compared) between two candidate folders' masks of one scene (every
    light's mask), or None when either has none or their sizes differ."""
    names = sorted(p.name for p in a_dir.glob("mask*.png")) if a_dir.is_dir() else []
    if not names or sorted(p.name for p in b_dir.glob("mask*.png")) != names:
        return None
    differ = total = 0
    for name in names:
        wa, ha, pa = grey_png(a_dir / name)
        wb, hb, pb = grey_png(b_dir / name)
        if (wa, ha) != (wb, hb):
            return None
        differ += sum(1 for x, y in zip(pa, pb) if x != y)
        total += wa * ha
    return differ, total


def diff_page(shadowref, r, twin, work):
    """`shadowref diff` of a run's verdicts against its twin's (the WebGL2 run is A, the run B): the
    side-by-side page <work>/backends/<run>-vs-<twin>/diff.html; returns its path relative to work and
    the diff's summary line."""
    rel = pathlib.Path("backends") / f"{r['run']}-vs-{twin['run']}"
    p = run([shadowref, "diff", work / "verdicts" / twin["run"], work / "verdicts" / r["run"], "--out", work / rel],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode not in (0, 1):  # 0 nothing changed, 1 changes found; others are errors
        sys.exit(f"{r['run']}: shadowref diff against {twin['run']} failed (exit {p.returncode}):\n{p.stdout}")
    summary = next((line for line in p.stdout.splitlines() if " cases compared, " in line), "")
    return rel / "diff.html", summary


def backend_comparison(pairs, work, pages):
    """Lines of the backends' comparison: per run with a twin, per scene, each one's verdict and how
    many mask pixels differ between the two backends' masks, and the link to the pair's diff page
    (`pages`: run name -> (page relative to work, summary line))."""
    lines = ["# Backend against backend", "",
             "Per scene: the WebGL2 twin's verdict, the WebGPU run's, and how many mask pixels differ between the two "
             "backends' masks (all lights; of the pixels compared).", ""]
    for r, twin, observed, twin_observed in pairs:
        page, summary = pages[r["run"]]
        lines += [f"## {r['run']} (twin {twin['run']})", "",
                  f"Side by side, every case that differs: [{page.as_posix()}]({page.as_posix()}) ({summary}).", "",
                  "| scene | " + twin["run"] + " | " + r["run"] + " | pixels differ |", "| --- | --- | --- | --- |"]
        for scene in sorted(set(observed) | set(twin_observed)):
            d = mask_difference(work / "renders" / twin["run"] / scene, work / "renders" / r["run"] / scene)
            diff = "—" if d is None else f"{d[0]} of {d[1]}"
            lines.append(f"| {scene} | {twin_observed.get(scene, '—')} | {observed.get(scene, '—')} | {diff} |")
        lines.append("")
    return lines


def differences(recorded, observed):
    """Lines naming every scene whose verdict differs between the recorded table and this run."""
    lines = []
    for scene in sorted(set(recorded) | set(observed)):
        want = recorded.get(scene, {}).get("verdict")
        got = observed.get(scene)
        if want != got:
            lines.append(f"  {scene}: recorded {want or '(none)'}, now {got or '(none)'}")
    return lines


def recorded_entry(before, status):
    """The table's entry for a scene now `status`: its why and cause kept only if the verdict stayed."""
    if status == "PASS":
        return {"verdict": status}
    if before.get("verdict") == status:
        return {"verdict": status, "why": before.get("why", ""), "cause": before.get("cause", "")}
    return {"verdict": status, "why": "", "cause": ""}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shadowref", required=True, type=pathlib.Path)
    ap.add_argument("--irrlicht", required=True, type=pathlib.Path)
    ap.add_argument("--osg", required=True, type=pathlib.Path)
    ap.add_argument("--work", required=True, type=pathlib.Path)
    ap.add_argument("--verdicts", type=pathlib.Path, default=HERE / "verdicts.json")
    ap.add_argument("--record", action="store_true", help="rewrite the recorded verdicts from this run")
    ap.add_argument("--runs", default="*", help="comma-separated globs over the run names (default: every run)")
    ap.add_argument("--resolving-power", action="store_true",
                    help="give each verdict its resolving power in the reports (always with --record)")
    a = ap.parse_args()
    patterns = a.runs.split(",")

    start = time.monotonic()
    table = json.loads(a.verdicts.read_text())
    exes = {"irrlicht": a.irrlicht.resolve(), "osg": a.osg.resolve()}
    work = a.work.resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    pack, cache = work / "pack", work / "reference-cache"
    p = run([a.shadowref, "export", "--out", pack], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        sys.exit(f"shadowref export failed (exit {p.returncode}):\n{p.stdout}")

    if any(r["harness"] in WEB_HARNESSES for r in table["runs"]) and web_ready():
        sys.exit(f"the web harnesses need {web_ready()}")

    failed = False
    observed_by_run = {}
    selected = [r for r in table["runs"] if any(fnmatch.fnmatchcase(r["run"], p) for p in patterns)]
    for (engine, backend), runs in web_batches(selected):
        t0 = time.monotonic()
        render_web_batch(engine, backend, runs, pack, work)
        print(f"{engine} on {backend}: {len(runs)} run(s) rendered in one browser  ({time.monotonic() - t0:.1f} s)")
    for r in selected:
        t0 = time.monotonic()
        candidates, verdict_dir = work / "renders" / r["run"], work / "verdicts" / r["run"]
        if r["harness"] not in WEB_HARNESSES:
            render(r, exes, pack, candidates, work)
        scenes = judged_scenes(r, pack, not_judged_on(table, r["harness"]))
        observed = judge(r, a.shadowref.resolve(), pack, candidates, verdict_dir, cache, scenes, a.record or a.resolving_power)
        observed_by_run[r["run"]] = observed
        diff = differences(r["verdicts"], observed)
        counts = {}
        for status in observed.values():
            counts[status] = counts.get(status, 0) + 1
        summary = ", ".join(f"{n} {s}" for s, n in sorted(counts.items()))
        print(f"{r['run']:<28} {r['technique']:<14} {summary}  ({time.monotonic() - t0:.1f} s)")
        if a.record:
            r["verdicts"] = {scene: recorded_entry(r["verdicts"].get(scene, {}), status)
                             for scene, status in sorted(observed.items())}
        elif diff:
            failed = True
            print(f"{r['run']}: verdicts differ from {a.verdicts.name}:\n" + "\n".join(diff) +
                  f"\n  look at {verdict_dir / 'report' / 'index.html'}")

    runs = {r["run"]: r for r in table["runs"]}
    for r in table["runs"]:
        if r.get("twin") and r["twin"] not in runs:
            sys.exit(f"{r['run']}: its twin {r['twin']} is not a run of {a.verdicts.name}")
    pairs = [(r, runs[r["twin"]], observed_by_run[r["run"]], observed_by_run[r["twin"]]) for r in table["runs"]
             if r.get("twin") and r["run"] in observed_by_run and r["twin"] in observed_by_run]
    if pairs:
        pages = {r["run"]: diff_page(a.shadowref.resolve(), r, twin, work) for r, twin, _, _ in pairs}
        lines = backend_comparison(pairs, work, pages)
        (work / "backends.md").write_text("\n".join(lines) + "\n")
        print("\n".join(lines[4:]) + f"written to {work / 'backends.md'}")

    # The comparison has teeth: a recorded verdict flipped in memory must be reported.
    probe = table["runs"][0]
    scene = sorted(probe["verdicts"])[0]
    flipped = dict(probe["verdicts"], **{scene: {"verdict": "NOT-" + probe["verdicts"][scene]["verdict"]}})
    if not differences(flipped, {s: v["verdict"] for s, v in probe["verdicts"].items()}):
        sys.exit("self-check: a changed verdict went unnoticed")

    if a.record:
        a.verdicts.write_text(json.dumps(table, indent=2, ensure_ascii=False) + "\n")
        print(f"recorded {a.verdicts}; write the why of every non-PASS, then engines/readme_table.py --update")
    print(f"engines: {'FAILED' if failed else 'all verdicts as recorded'} in {time.monotonic() - start:.1f} s;"
          f" reports under {work / 'verdicts'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
