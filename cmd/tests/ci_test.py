#!/usr/bin/env python3
"""End-to-end tests of `shadowref conform` in an engine team's CI (docs/ci.md), one CTest test per part:

  shards        four shards as separate processes, once by --shard and once by each CI's environment
                protocol (Bazel TEST_*, GoogleTest GTEST_*, GitLab CI_NODE_*), each merged: the merged
                report.json's cases (status, metrics, images byte for byte) equal an unsplit run's, time
                and provenance aside; the shard status file is touched and XML_OUTPUT_FILE written; two
                shards balanced by the unsplit run's times (--shard-weights) merge to the same; a scene added
                to the catalogue changes the recorded plan for that scene alone.
  refusals      `shadowref merge` refuses a missing shard, a duplicate shard, a case seen twice, a mixed
                suite version, convention and declaration, each with one line on stderr, exit 4, and
                nothing written.
  expectations  an expectations file of the candidate's known FAILs: exit 0; one PASSing scene's mask
                inverted: exit 2 and that case named a new failure; the known FAIL's mask replaced by our
                correct render: named an improvement (exit 1); expectations-update.txt makes the next
                run green; a line limited to WebGPU (api=webgpu) holds for the case's WebGPU render (exit 0)
                and not for its right WebGL2 render (green, exit 0, neither stale nor an improvement); a bad
                line is one line naming file and line, exit 4, nothing written.
                The candidate is our own renders with three.js r187 BasicShadowMap's recorded FAIL
                (engines/verdicts.json: light_near_caster, the plate inside the point light's near
                plane, its shadow lit) put in by hand: the plate's shadow removed from the mask.
                With --three-pack, the candidate is three.js itself (engines/web), as engines.verdicts
                renders it.

usage: ci_test.py --shadowref EXE --work DIR PART [--three-pack]
"""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time
import zlib

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts"))
from png8 import read_png, write_png  # noqa: E402 (the project's scripts folder)

SCENES = "directional_light,camera_at_light,ground_sphere,light_near_caster"  # one per shard of 4 by their hash
TECHNIQUES = "shadowmap,planar"


def fail(msg):
    sys.exit("FAILED: " + msg)


def run(args, env=None, expect=None):
    full_env = dict(os.environ)
    for k in ("TEST_TOTAL_SHARDS", "TEST_SHARD_INDEX", "GTEST_TOTAL_SHARDS", "GTEST_SHARD_INDEX", "CI_NODE_TOTAL",
              "CI_NODE_INDEX", "TEST_SHARD_STATUS_FILE", "GTEST_SHARD_STATUS_FILE", "XML_OUTPUT_FILE"):
        full_env.pop(k, None)
    full_env.update(env or {})
    p = subprocess.run([str(a) for a in args], env=full_env, capture_output=True, text=True)
    if expect is not None and p.returncode != expect:
        fail(f"{' '.join(map(str, args))}: exit {p.returncode}, expected {expect}\nstdout:\n{p.stdout}\nstderr:\n{p.stderr}")
    return p


# -- reports ----------------------------------------------------------------------------------------
PROVENANCE = ("seconds", "frame_ms", "candidate_dir", "reference_dir", "shard", "host")
IMAGE_KEYS = ("reference", "decided", "candidate", "error", "candidate_visibility", "visibility_error")


def cases_of(out):
    """report.json's cases without time and provenance, each image replaced by its bytes' hash."""
    report = json.loads((out / "report.json").read_text())
    cases = []
    for c in report["cases"]:
        c = {k: v for k, v in c.items() if k not in PROVENANCE}
        for l in c.get("lights", []):
            for k in IMAGE_KEYS:
                if l.get(k):
                    l[k] = (l[k], zlib.crc32((out / "report" / l[k]).read_bytes()))
        for k in ("shaded", "reference_shaded"):
            if c.get(k):
                c[k] = (c[k], zlib.crc32((out / "report" / c[k]).read_bytes()))
        cases.append(c)
    return cases, report


def conform(exe, work, out, *extra, env=None, expect=0):
    return run([exe, "conform", "--scenes", SCENES, "--techniques", TECHNIQUES, "--out", work / out, "--cache",
                work / "cache", "--jobs", "1", "--quiet", *extra], env=env, expect=expect)


def part_shards(exe, work):
    conform(exe, work, "whole")
    whole, _ = cases_of(work / "whole")
    if len(whole) != 8:
        fail(f"the unsplit run has {len(whole)} cases, expected 8")
    protocols = {
        "flag": lambda k: ({}, ["--shard", f"{k + 1}/4"]),
        "bazel": lambda k: ({"TEST_TOTAL_SHARDS": "4", "TEST_SHARD_INDEX": str(k),
                             "TEST_SHARD_STATUS_FILE": str(work / f"bazel-status-{k}"),
                             "XML_OUTPUT_FILE": str(work / f"bazel-{k}.xml")}, []),
        "gtest": lambda k: ({"GTEST_TOTAL_SHARDS": "4", "GTEST_SHARD_INDEX": str(k),
                             "GTEST_SHARD_STATUS_FILE": str(work / f"gtest-status-{k}")}, []),
        "gitlab": lambda k: ({"CI_NODE_TOTAL": "4", "CI_NODE_INDEX": str(k + 1)}, []),
    }
    for name, protocol in protocols.items():
        ran = []
        for k in range(4):
            env, flags = protocol(k)
            p = conform(exe, work, f"{name}-{k + 1}", *flags, env=env)
            if f"shard {k + 1}/4" not in p.stdout or "control case" not in p.stdout:
                fail(f"{name} shard {k + 1}: does not say which shard it is and what it ran:\n{p.stdout}")
            report = json.loads((work / f"{name}-{k + 1}" / "report.json").read_text())
            ran += [c["scene"] for c in report["cases"]]
            if len(report["plan"]["scenes"]) != 4 or report["shard"]["index"] != k + 1:
                fail(f"{name} shard {k + 1}: report.json's plan or shard: {report['plan']} {report.get('shard')}")
            if report["shard"]["control"]["status"] != "PASS":
                fail(f"{name} shard {k + 1}: control case {report['shard']['control']}")
        if sorted(set(ran)) != sorted(SCENES.split(",")):
            fail(f"{name}: the shards ran {sorted(ran)}, not every scene once")
        run([exe, "merge", *[work / f"{name}-{k + 1}" for k in range(4)], "--out", work / f"{name}-merged"], expect=0)
        merged, report = cases_of(work / f"{name}-merged")
        if merged != whole:
            for a, b in zip(whole, merged):
                if a != b:
                    fail(f"{name}: merged case differs from the unsplit run's:\n{a}\n{b}")
            fail(f"{name}: {len(merged)} merged cases, {len(whole)} unsplit")
        if any("shard" not in c or "host" not in c for c in report["cases"]):
            fail(f"{name}: a merged case does not say its shard and host")
        for f in ("report.junit.xml", "summary.md", "report/index.html"):
            if not (work / f"{name}-merged" / f).is_file():
                fail(f"{name}: the merge wrote no {f}")
        print(f"{name}: 4 shards merged equal the unsplit run ({len(merged)} cases)")
    # Balanced by the unsplit run's recorded times: two shards, the plan says so, the merge is the same.
    for k in range(2):
        conform(exe, work, f"weighed-{k + 1}", "--shard", f"{k + 1}/2", "--shard-weights", work / "whole" / "report.json")
        plan = json.loads((work / f"weighed-{k + 1}" / "report.json").read_text())["plan"]
        if plan["assignment"] != "weights" or sorted({p["shard"] for p in plan["scenes"]}) != [1, 2]:
            fail(f"--shard-weights: plan {plan}")
    run([exe, "merge", work / "weighed-1", work / "weighed-2", "--out", work / "weighed-merged"], expect=0)
    if cases_of(work / "weighed-merged")[0] != whole:
        fail("--shard-weights: the merged cases differ from the unsplit run's")
    # A scene added to the catalogue moves only itself: the plan every shard records, before and after.
    source = pathlib.Path(__file__).resolve().parents[2] / "conformance" / "scenes"
    for name, extra in (("before", []), ("after", ["added_scene"])):
        cat = work / f"catalogue-{name}"
        cat.mkdir()
        for scene in SCENES.split(","):
            shutil.copy(source / f"{scene}.json", cat / f"{scene}.json")
        for scene in extra:
            text = json.loads((source / "ground_sphere.json").read_text())
            text["name"] = scene
            (cat / f"{scene}.json").write_text(json.dumps(text))
        run([exe, "conform", "--catalogue", cat, "--techniques", "planar", "--out", work / f"plan-{name}", "--cache",
             work / "cache", "--jobs", "1", "--quiet", "--shard", "1/4"], expect=0)
    plans = [{p["scene"]: p["shard"] for p in json.loads((work / f"plan-{n}" / "report.json").read_text())["plan"]["scenes"]}
             for n in ("before", "after")]
    moved = {s for s in plans[1] if plans[0].get(s) != plans[1][s]}
    if moved != {"added_scene"}:
        fail(f"adding a scene changed the shard of {sorted(moved)}: {plans}")
    for k in range(4):
        for f in (f"bazel-status-{k}", f"gtest-status-{k}", f"bazel-{k}.xml"):
            if not (work / f).is_file():
                fail(f"{f} was not written: the runner would say the binary does not shard")


def part_refusals(exe, work):
    for k in range(4):
        conform(exe, work, f"s{k + 1}", "--shard", f"{k + 1}/4")
    shards = [work / f"s{k + 1}" for k in range(4)]

    def refused(name, dirs, needle):
        out = work / f"merged-{name}"
        p = run([exe, "merge", *dirs, "--out", out], expect=4)
        lines = p.stderr.strip().splitlines()
        if len(lines) != 1 or needle not in lines[0]:
            fail(f"{name}: expected one line with '{needle}', got:\n{p.stderr}")
        if out.exists():
            fail(f"{name}: a refused merge wrote {out}")
        print(f"{name}: {lines[0]}")

    refused("missing-shard", shards[:3], "shard 4/4 missing")
    refused("duplicate-shard", shards + [shards[1]], "shard 2/4 given twice")
    # A case seen twice: shard 3 made to hold shard 1's first case too.
    dup = work / "s3-dup"
    shutil.copytree(shards[2], dup)
    r3, r1 = (json.loads((d / "report.json").read_text()) for d in (dup, shards[0]))
    r3["cases"].append(r1["cases"][0])
    (dup / "report.json").write_text(json.dumps(r3))
    refused("duplicate-case", [shards[0], shards[1], dup, shards[3]], "seen twice")
    mixed = work / "s2-other-version"
    shutil.copytree(shards[1], mixed)
    r2 = json.loads((mixed / "report.json").read_text())
    r2["version"] = "0.0.9"
    (mixed / "report.json").write_text(json.dumps(r2))
    refused("mixed-version", [shards[0], mixed, shards[2], shards[3]], "suite version 0.0.9")
    conform(exe, work, "s2-d3d", "--shard", "2/4", "--convention", "d3d")
    refused("mixed-convention", [shards[0], work / "s2-d3d", shards[2], shards[3]], "convention d3d")
    conform(exe, work, "s2-map", "--shard", "2/4", "--shadow-map-size", "512")
    refused("mixed-declarations", [shards[0], work / "s2-map", shards[2], shards[3]], "declarations")


def part_expectations(exe, work, three_pack):
    catalogue, technique, scenes = [], "shadowmap", SCENES.split(",")
    if three_pack:
        candidates, catalogue, known, not_judged = three_candidates(exe, work)
        scenes = sorted(p.name for p in candidates.iterdir() if p.name not in not_judged)
    else:
        candidates, known = our_candidates(exe, work)
    fails = work / "expectations.txt"
    fails.write_text("# three.js r187 BasicShadowMap, engines/verdicts.json\n" +
                     "".join(f"{s}@{technique},FAIL  # {why[:60]}\n" for s, why in known.items()) + "[flakes]\n^no_such_scene@\n")

    def judge(folder, out, expect, *extra):
        return run([exe, "conform", *catalogue, "--scenes", ",".join(scenes), "--candidate-dir", folder, "--technique",
                    technique, "--out", work / out, "--cache", work / "cache", "--jobs", "1", "--quiet", *extra], expect=expect)

    judge(candidates, "plain", 2)  # the known FAILs fail a run without the file
    p = judge(candidates, "known", 0, "--expectations", fails)
    if "0 new failure(s)" not in p.stdout or f"{len(known)} known" not in p.stdout:
        fail(f"known failures not counted as such:\n{p.stdout}")
    report = json.loads((work / "known" / "report.json").read_text())
    if report["expectations"]["counts"]["expected"] != len(known) or 'skipped="' + str(len(known)) not in (work / "known" / "report.junit.xml").read_text():
        fail(f"report.json / JUnit do not show the known failures: {report['expectations']}")
    # One PASSing scene's mask inverted: a new failure, named.
    passing = next(s for s in scenes if s not in known)
    worse = work / "worse"
    shutil.copytree(candidates, worse, symlinks=False)
    mask = worse / passing / "mask.png"
    w, h, rows = read_png(mask)
    write_png(mask, w, h, [bytearray(255 - v if v in (0, 255) else v for v in r) for r in rows])
    p = judge(worse, "worse", 2, "--expectations", fails)
    if f"NEW FAILURE {passing}@{technique}" not in p.stdout:
        fail(f"the inverted {passing} is not named a new failure:\n{p.stdout}")
    for f, needle in (("summary.md", "new-failure"), ("report.junit.xml", "new failure: FAIL"), ("report/index.html", "new failure")):
        if needle not in (work / "worse" / f).read_text():
            fail(f"{f} does not show the new failure ('{needle}')")
    # The known FAIL's mask replaced by our correct render: an improvement, named.
    better = work / "better"
    shutil.copytree(candidates, better, symlinks=False)
    fixed = next(iter(known))
    shutil.copy(our_render(exe, work, catalogue, fixed) / "mask.png", better / fixed / "mask.png")
    p = judge(better, "better", 1, "--expectations", fails)
    if f"IMPROVEMENT {fixed}@{technique}" not in p.stdout or "remove that line" not in p.stdout:
        fail(f"the fixed {fixed} is not named an improvement:\n{p.stdout}")
    if "improvement" not in (work / "better" / "report.junit.xml").read_text():
        fail("JUnit does not show the improvement")
    # The next file makes the next run of the same folder green.
    update = (work / "better" / "expectations-update.txt").read_text()
    if f"{fixed}@{technique}," in update:
        fail(f"expectations-update.txt keeps the improved line:\n{update}")
    (work / "next.txt").write_text(update)
    judge(better, "better-again", 0, "--expectations", work / "next.txt")
    # A stale line is reported, and the run stays green.
    (work / "stale.txt").write_text(fails.read_text().replace("[flakes]", "gone_scene@shadowmap,FAIL\n[flakes]"))
    p = judge(candidates, "stale", 0, "--expectations", work / "stale.txt")
    if "STALE" not in p.stdout or "gone_scene" not in p.stdout:
        fail(f"the stale line is not reported:\n{p.stdout}")
    # A FAIL known on WebGPU only (a line limited to an environment): the WebGPU run of the case is
    # known (exit 0); its WebGL2 run, right, is green (exit 0); neither names a stale line or an improvement.
    known_scene = next(iter(known))
    (work / "webgpu.txt").write_text(f"{known_scene}@{technique},FAIL,api=webgpu  # seen on WebGPU alone\n")

    def with_environment(folder, name, api):
        out = work / name
        shutil.copytree(folder, out, symlinks=False)
        for scene_dir in (p for p in out.iterdir() if p.is_dir()):
            declared = scene_dir / "candidate.json"
            d = json.loads(declared.read_text()) if declared.exists() else {}
            d["environment"] = {"api": api, "adapter": "google swiftshader", "engine": "this test"}
            declared.write_text(json.dumps(d))
        return out

    right = work / "right"
    shutil.copytree(candidates, right, symlinks=False)
    shutil.copy(our_render(exe, work, catalogue, known_scene) / "mask.png", right / known_scene / "mask.png")
    for folder, name, api, line in ((candidates, "on-webgpu", "webgpu", "1 known"), (right, "on-webgl2", "webgl2", "0 known")):
        p = run([exe, "conform", *catalogue, "--scenes", known_scene, "--candidate-dir", with_environment(folder, name + "-in", api),
                 "--technique", technique, "--out", work / name, "--cache", work / "cache", "--jobs", "1", "--quiet",
                 "--expectations", work / "webgpu.txt"], expect=0)
        if line not in p.stdout or "STALE" in p.stdout or "IMPROVEMENT" in p.stdout:
            fail(f"{name}: the WebGPU-only line is not read as limited to WebGPU:\n{p.stdout}")
        if f"Rendered on: api {api}" not in (work / name / "summary.md").read_text():
            fail(f"{name}: summary.md does not say where the render came from")
    # Bad input: one line naming the file and line, exit 4, nothing written.
    (work / "bad.txt").write_text("# ok\nground_sphere@shadowmap,BROKEN\n")
    p = judge(candidates, "bad", 4, "--expectations", work / "bad.txt")
    if p.stderr.count("\n") != 1 or "bad.txt:2: unknown status 'BROKEN'" not in p.stderr or (work / "bad").exists():
        fail(f"bad expectations input: {p.stderr!r}, wrote: {(work / 'bad').exists()}")
    print(f"expectations: {len(known)} known, {passing} inverted = new failure, {fixed} fixed = improvement, next file green")


def our_render(exe, work, catalogue, scene):
    out = work / f"ours-{scene}"
    if not out.exists():
        run([exe, "conform", *catalogue, "--scenes", scene, "--techniques", "shadowmap", "--out", out, "--cache",
             work / "cache", "--jobs", "1", "--quiet"], expect=0)
    return out / "renders" / scene / "shadowmap"


def our_candidates(exe, work):
    """Our shadowmap renders, with three.js's recorded FAIL put in: light_near_caster's shadow lit."""
    verdicts = json.loads((pathlib.Path(__file__).resolve().parents[2] / "engines" / "verdicts.json").read_text())
    three = next(r for r in verdicts["runs"] if r["run"] == "three-basic")
    known = {s: v["why"] for s, v in three["verdicts"].items() if v["verdict"] == "FAIL" and s in SCENES.split(",")}
    if list(known) != ["light_near_caster"]:
        fail(f"engines/verdicts.json's three-basic FAILs among {SCENES} are {list(known)}: this test puts in light_near_caster's alone")
    out = work / "candidates"
    for scene in SCENES.split(","):
        (out / scene).mkdir(parents=True)
        shutil.copy(our_render(exe, work, [], scene) / "mask.png", out / scene / "mask.png")
    # three.js: the plate lies inside the point light's near plane, so it casts no shadow at all.
    w, h, rows = read_png(out / "light_near_caster" / "mask.png")
    write_png(out / "light_near_caster" / "mask.png", w, h, [bytearray(255 if v == 0 else v for v in r) for r in rows])
    return out, known


def three_candidates(exe, work):
    """three.js r187 BasicShadowMap's own renders of the pack (engines/web), its recorded FAILs, and the scenes
    verdicts.json does not judge on three.js (not_judged: the harness cannot give three.js what they need)."""
    here = pathlib.Path(__file__).resolve().parents[2]
    verdicts = json.loads((here / "engines" / "verdicts.json").read_text())
    three = next(r for r in verdicts["runs"] if r["run"] == "three-basic")
    known = {s: v["why"] for s, v in three["verdicts"].items() if v["verdict"] == "FAIL"}
    pack, out = work / "pack", work / "three-basic"
    run([exe, "export", "--out", pack, "--cache", work / "cache"], expect=0)
    run(["node", here / "engines" / "web" / "render.mjs", "--engine", "three", "--pack", pack, "--out", out,
         "--variant", "basic"], expect=0)
    not_judged = {s for entry in verdicts.get("not_judged", []) if "three" in entry["harnesses"] for s in entry["scenes"]}
    return out, ["--catalogue", pack / "scenes"], known, not_judged


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shadowref", required=True, type=pathlib.Path)
    ap.add_argument("--work", required=True, type=pathlib.Path)
    ap.add_argument("--three-pack", action="store_true")
    ap.add_argument("part", choices=("shards", "refusals", "expectations"))
    a = ap.parse_args()
    work = a.work.resolve() / a.part
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    t0 = time.monotonic()
    {"shards": lambda: part_shards(a.shadowref.resolve(), work),
     "refusals": lambda: part_refusals(a.shadowref.resolve(), work),
     "expectations": lambda: part_expectations(a.shadowref.resolve(), work, a.three_pack)}[a.part]()
    print(f"{a.part}: passed in {time.monotonic() - t0:.1f} s")


if __name__ == "__main__":
    main()
