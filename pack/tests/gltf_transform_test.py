#!/usr/bin/env python3
"""A glTF written by a tool other than ours is judged as ours is (docs/scene-format.md, "Your own glTF
scene"): the pack's scene.gltf of a catalogue scene (level_cut: dense meshes, an alpha-masked material,
a skin, a rect light's extras, every light type) rewritten by gltf-transform 4.3.0
(pack/tests/gltf_transform, pinned by its package-lock.json; scripts/setup.sh installs it; the last
release that runs on Debian 12's Node.js 18), then

  copy   `gltf-transform copy` to a binary .glb (one GLB buffer, gltf-transform's own accessor layout);
  weld   `gltf-transform weld` to a .gltf (the pack's three vertices per triangle welded into an indexed
         mesh: other vertex counts, other index accessors);

and for the original and each rewrite, `shadowref conform --scenes <file>` renders our techniques and
judges them. Demanded: every technique's verdict on each rewrite equals its verdict on the original,
and the original's verdicts are the catalogue's expectations read as a glTF scene carries none (pass
-> PASS, fail -> FAIL); each rewrite's reference masks equal the original's on every pixel both
decide (the scene read back is the same scene, not merely one judged alike); the weld really changed
the layout (fewer vertices than the pack's flat triangles), and the copy is binary glTF.

usage: gltf_transform_test.py --shadowref EXE --gltf-transform CLI_JS --work DIR [--node NODE] [--scene NAME]
       [--techniques LIST]
"""
import argparse
import json
import pathlib
import shutil
import struct
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts"))
from png8 import read_png  # noqa: E402 (the project's scripts folder)

SCENES = pathlib.Path(__file__).resolve().parents[2] / "conformance" / "scenes"


def fail(msg):
    sys.exit("FAILED: " + msg)


def run(args, expect=(0,)):
    p = subprocess.run([str(a) for a in args], capture_output=True, text=True)
    if p.returncode not in expect:
        fail(f"{' '.join(map(str, args))}: exit {p.returncode}, expected {expect}\nstdout:\n{p.stdout}\nstderr:\n{p.stderr}")
    return p


def verdicts(report):
    out = {}
    for case in json.loads(pathlib.Path(report).read_text())["cases"]:
        out[case["technique"]] = case["status"]
    return out


def gltf_json(path):
    """The JSON chunk of a .gltf or .glb."""
    data = pathlib.Path(path).read_bytes()
    if data[:4] == b"glTF":
        n = struct.unpack("<I", data[12:16])[0]
        return json.loads(data[20:20 + n])
    return json.loads(data)


def vertex_count(doc):
    return sum(doc["accessors"][p["attributes"]["POSITION"]]["count"] for m in doc["meshes"] for p in m["primitives"])


def same_reference(a, b, lights, what):
    """Every light's mask equal on the pixels both references decide."""
    for i in range(lights):
        wa, ha, ma = read_png(a / f"mask_{i}.png")
        wb, hb, mb = read_png(b / f"mask_{i}.png")
        _, _, da = read_png(a / f"decided_{i}.png")
        _, _, db = read_png(b / f"decided_{i}.png")
        if (wa, ha) != (wb, hb):
            fail(f"{what}: light {i}: reference {wb}x{hb}, the original's {wa}x{ha}")
        differ = sum(1 for y in range(ha) for x in range(wa) if da[y][x] and db[y][x] and ma[y][x] != mb[y][x])
        decided = sum(1 for y in range(ha) for x in range(wa) if da[y][x] and db[y][x])
        if differ or decided == 0:
            fail(f"{what}: light {i}: {differ} of {decided} pixels decided by both differ from the original's reference")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--shadowref", required=True)
    ap.add_argument("--gltf-transform", required=True, help="gltf-transform's cli.js")
    ap.add_argument("--node", default="node")
    ap.add_argument("--work", required=True)
    ap.add_argument("--scene", default="level_cut")
    ap.add_argument("--techniques", default="")
    a = ap.parse_args()
    tool = pathlib.Path(a.gltf_transform)
    if not tool.exists():
        fail(f"{tool} is missing (npm ci in {tool.parents[4]}, which scripts/setup.sh runs)")
    work = pathlib.Path(a.work)
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    cache = work / "cache"
    techniques = ["--techniques", a.techniques] if a.techniques else []

    run([a.shadowref, "export", "--scenes", a.scene, "--out", work / "pack", "--cache", cache])
    # The pack's scene.gltf, in a folder of its own under the scene's name (the file's stem names the scene).
    original = work / "original" / f"{a.scene}.gltf"
    shutil.copytree(work / "pack" / a.scene, original.parent)
    (original.parent / "scene.gltf").rename(original)
    rewrites = {"copy": work / "copy" / f"{a.scene}.glb", "weld": work / "weld" / f"{a.scene}.gltf"}
    for how, out in rewrites.items():
        out.parent.mkdir()
        run([a.node, tool, how, original, out])
    if rewrites["copy"].read_bytes()[:4] != b"glTF":
        fail("gltf-transform copy did not write a binary glTF")
    flat, welded = vertex_count(gltf_json(original)), vertex_count(gltf_json(rewrites["weld"]))
    if not welded < flat:
        fail(f"gltf-transform weld left {welded} vertices of the original's {flat}: the layout did not change")

    expect = json.loads((SCENES / f"{a.scene}.json").read_text())["expect"]
    lights = len(gltf_json(original)["extensions"]["KHR_lights_punctual"]["lights"])
    got = {}
    for name, path in [("original", original)] + list(rewrites.items()):
        out = work / f"conform-{name}"
        # exit 2: a glTF scene carries no expectations, so the catalogue's expected failures read FAIL
        run([a.shadowref, "conform", "--scenes", path, "--out", out, "--cache", cache, "--quiet"] + techniques, expect=(0, 2))
        got[name] = verdicts(out / "report.json")
        run([a.shadowref, "reference", "--scene", path, "--out", work / f"reference-{name}"])
    # An expected failure that shows only from an image height on ("from_height") passes below it.
    height = json.loads((SCENES / f"{a.scene}.json").read_text())["resolution"][1]
    want = {t: "PASS" if e["result"] == "pass" or height < e.get("from_height", 0) else "FAIL"
            for t, e in expect.items() if t in got["original"]}
    if not got["original"] or got["original"] != want:
        fail(f"the pack's scene.gltf: verdicts {got['original']}, the catalogue's expectations read as a glTF scene's {want}")
    for name in rewrites:
        if got[name] != got["original"]:
            fail(f"gltf-transform {name}: verdicts {got[name]}, the original's {got['original']}")
        same_reference(work / "reference-original", work / f"reference-{name}", lights, f"gltf-transform {name}")
    print(f"{a.scene}: the original and gltf-transform copy (.glb) and weld ({flat} -> {welded} vertices) judged alike: "
          + ", ".join(f"{t} {s}" for t, s in sorted(got["original"].items())))


if __name__ == "__main__":
    main()
