#!/usr/bin/python3
"""engines/refusal_test.py — the test engines.webgpu_refusal: a web harness asked for WebGPU refuses
to render on anything else.

For three.js (WebGPURenderer, which would silently fall back to its WebGL2 backend) and Babylon.js
(WebGPUEngine), render.mjs --backend webgpu is started in a Chromium without the flags that give it
WebGPU: it must exit non-zero with one line saying so and write nothing. The control, the same
command with the flags, must start on a WebGPU adapter (so the refusal is about the backend, not a
harness that always fails). The pack is a manifest without scenes: no scene is needed for either.

  refusal_test.py [--node EXE] [--chromium EXE]
"""

import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--node", default="node")
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    a = ap.parse_args()
    problems = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        (tmp / "pack").mkdir()
        (tmp / "pack" / "manifest.json").write_text(json.dumps({"scenes": []}))
        for engine in ("three", "babylon"):
            for flags in (False, True):
                out = tmp / f"out-{engine}-{flags}"
                cmd = [a.node, HERE / "web" / "render.mjs", "--engine", engine, "--backend", "webgpu", "--pack", tmp / "pack",
                       "--out", out, "--variant", "basic" if engine == "three" else "none", "--chromium", a.chromium]
                if not flags:
                    cmd.append("--no-webgpu-flags")
                p = subprocess.run([str(c) for c in cmd], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
                lines = p.stdout.splitlines()
                what = f"{engine}, {'with' if flags else 'without'} the WebGPU flags"
                if flags:
                    env = [json.loads(x.split(": ", 1)[1]) for x in lines if x.startswith("environment: ")]
                    if p.returncode != 0 or len(env) != 1 or env[0].get("api") != "webgpu":
                        problems.append(f"{what}: expected a start on WebGPU (exit 0, environment api webgpu), got exit "
                                        f"{p.returncode}:\n{p.stdout}")
                    continue
                if p.returncode == 0 or len(lines) != 1 or not lines[0].startswith("render.mjs: asked for") \
                        or "no mask written" not in lines[0]:
                    problems.append(f"{what}: expected exit 1 and one line of refusal, got exit {p.returncode}:\n{p.stdout}")
                if out.exists() and any(out.rglob("*")):
                    problems.append(f"{what}: wrote {sorted(str(f) for f in out.rglob('*'))}")
                print(f"{what}: {lines[0] if lines else '(nothing)'} (exit {p.returncode})")
    for line in problems:
        print(line, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
