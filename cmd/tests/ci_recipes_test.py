#!/usr/bin/env python3
"""The CI recipes of docs/ci.md, each run as its CI system would run it (one CTest test per recipe):

  gitlab    docs/ci/gitlab-ci.yml: the `parallel: 4` job's script four times with CI_NODE_INDEX 1..4 and
            CI_NODE_TOTAL 4, then the report stage's script; its artifacts and JUnit report exist.
  github    docs/ci/github-actions.yml: every `run:` step of the judge job once per matrix value, with
            `${{ matrix.shard }}` put in, then the report job's (the `uses:` steps move files between
            machines; here the jobs share one folder); $GITHUB_STEP_SUMMARY gets the summary.
  bazel     docs/ci/BUILD.bazel's sh_test: shadows_test.sh once per shard of its shard_count with the
            environment Bazel sets (TEST_TOTAL_SHARDS, TEST_SHARD_INDEX, TEST_SHARD_STATUS_FILE,
            XML_OUTPUT_FILE, TEST_UNDECLARED_OUTPUTS_DIR), then the merge its comment gives; every status
            file touched and every XML file written.
  ctest     docs/ci/CMakeLists.txt configured and run by ctest (four shards, then the merge).

Each judges the same candidate, our renders with three.js's recorded FAIL put in (ci_test.py), under an
expectations file that lists it: every recipe must end green with that case a known failure. The
`shadowref` the recipes call is the build's, through a wrapper that keeps the run to four scenes and
a shared reference cache (--scenes, --cache, --jobs 1, --quiet), so that each recipe takes seconds.

usage: ci_recipes_test.py --shadowref EXE --work DIR gitlab|github|bazel|ctest
"""
import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import ci_test  # noqa: E402

RECIPES = pathlib.Path(__file__).resolve().parents[2] / "docs" / "ci"


def fail(msg):
    sys.exit("FAILED: " + msg)


def workspace(exe, work):
    """The engine team's checkout: renders, its expectations file, its render script, and shadowref on PATH."""
    (work / "prep").mkdir()
    prepared, known = ci_test.our_candidates(exe, work / "prep")
    ws = work / "ws"
    ws.mkdir()
    (ws / "shadows-expectations.txt").write_text(
        "# three.js r187 BasicShadowMap: the point light's shadow camera near plane is 0.5 (engines/verdicts.json)\n" +
        "".join(f"{s}@shadowmap,FAIL\n" for s in known))
    script = ws / "render-with-my-engine.sh"
    script.write_text(f"#!/bin/sh\n# The engine renders the pack; here, the prepared renders.\nrm -rf \"$1\" && cp -r {prepared} \"$1\"\n")
    script.chmod(0o755)
    bindir = work / "bin"
    bindir.mkdir()
    wrapper = bindir / "shadowref"
    wrapper.write_text("#!/bin/sh\n# The build's shadowref, kept to four scenes and one reference cache.\n"
                       f"if [ \"$1\" = conform ]; then shift; exec {exe} conform --scenes {ci_test.SCENES} "
                       f"--cache {work / 'prep' / 'cache'} --jobs 1 --quiet \"$@\"; fi\nexec {exe} \"$@\"\n")
    wrapper.chmod(0o755)
    return ws, bindir, known


def sh(line, ws, bindir, env=None, expect=0):
    full = {k: v for k, v in os.environ.items() if not re.match(r"(TEST_|GTEST_|CI_NODE_|XML_OUTPUT_FILE)", k)}
    full.update(env or {})
    full["PATH"] = f"{bindir}:{full['PATH']}"
    p = subprocess.run(["bash", "-ec", line], cwd=ws, env=full, capture_output=True, text=True)
    if p.returncode != expect:
        fail(f"{line}\nexit {p.returncode}, expected {expect}\n{p.stdout}\n{p.stderr}")
    return p


def check_merged(out, known):
    report = json.loads((out / "report.json").read_text())
    scenes = sorted({c["scene"] for c in report["cases"]})
    if scenes != sorted(ci_test.SCENES.split(",")):
        fail(f"{out}: the merged report holds {scenes}")
    if report["summary"]["exit_code"] != 0 or report["expectations"]["counts"]["expected"] != len(known):
        fail(f"{out}: summary {report['summary']}, expectations {report['expectations']['counts']}")
    if not (out / "report.junit.xml").is_file() or not (out / "report" / "index.html").is_file():
        fail(f"{out}: no JUnit or HTML")


def load_yaml(path):
    try:
        import yaml
    except ImportError:
        fail("python3-yaml is needed to read the recipe (scripts/setup.sh installs it)")
    return yaml.safe_load(path.read_text())


def gitlab(ws, bindir, known):
    ci = load_yaml(RECIPES / "gitlab-ci.yml")
    for stage in ci["stages"]:
        for name, job in ci.items():
            if not isinstance(job, dict) or job.get("stage") != stage:
                continue
            n = job.get("parallel", 1)
            for k in range(1, n + 1):
                env = {"CI_NODE_INDEX": str(k), "CI_NODE_TOTAL": str(n)} if "parallel" in job else {}
                for line in job["script"]:
                    sh(line, ws, bindir, env)
                for path in job.get("artifacts", {}).get("paths", []):
                    if not (ws / path.replace("$CI_NODE_INDEX", str(k))).exists():
                        fail(f"{name} #{k}: artifact {path} missing")
            junit = job.get("artifacts", {}).get("reports", {}).get("junit")
            if junit and not (ws / junit).is_file():
                fail(f"{name}: JUnit report {junit} missing")
    check_merged(ws / "shadows", known)


def github(ws, bindir, known):
    wf = load_yaml(RECIPES / "github-actions.yml")
    summary = ws / "step-summary.md"
    for name in ("judge", "report"):
        job = wf["jobs"][name]
        matrix = job.get("strategy", {}).get("matrix", {}).get("shard", [None])
        for shard in matrix:
            for step in job["steps"]:
                if "run" in step:
                    sh(step["run"].replace("${{ matrix.shard }}", str(shard)), ws, bindir, {"GITHUB_STEP_SUMMARY": str(summary)})
    check_merged(ws / "shadows", known)
    if "shadowref conform" not in summary.read_text():
        fail("$GITHUB_STEP_SUMMARY did not get the summary")


def bazel(ws, bindir, known):
    build = (RECIPES / "BUILD.bazel").read_text()
    shards = int(re.search(r"shard_count\s*=\s*(\d+)", build).group(1))
    script = RECIPES / re.search(r'srcs\s*=\s*\["([^"]+)"\]', build).group(1)
    sh("./render-with-my-engine.sh renders", ws, bindir)
    logs = ws / "bazel-testlogs" / "shadows"
    for k in range(shards):
        shard = logs / f"shard_{k + 1}_of_{shards}"
        (shard / "test.outputs").mkdir(parents=True)
        env = {"TEST_TOTAL_SHARDS": str(shards), "TEST_SHARD_INDEX": str(k), "TEST_SHARD_STATUS_FILE": str(shard / "status"),
               "XML_OUTPUT_FILE": str(shard / "test.xml"), "TEST_UNDECLARED_OUTPUTS_DIR": str(shard / "test.outputs")}
        sh(str(script), ws, bindir, env)
        for f in ("status", "test.xml"):
            if not (shard / f).is_file():
                fail(f"shard {k}: {f} not written: Bazel would fail the test (status) or lose its results (XML)")
    merge = re.search(r"#\s+(shadowref merge .*)", script.read_text()).group(1)
    sh(merge.replace("<package>/", ""), ws, bindir)
    check_merged(ws / "shadows", known)


def ctest(ws, bindir, known):
    sh("./render-with-my-engine.sh renders", ws, bindir)
    build = ws / "ctest-build"
    sh(f"cmake -S {RECIPES} -B {build} -DRENDERS={ws / 'renders'} -DEXPECTATIONS={ws / 'shadows-expectations.txt'}", ws, bindir)
    sh(f"ctest --test-dir {build} -j2 --output-on-failure", ws, bindir)
    check_merged(build / "shadows", known)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shadowref", required=True, type=pathlib.Path)
    ap.add_argument("--work", required=True, type=pathlib.Path)
    ap.add_argument("recipe", choices=("gitlab", "github", "bazel", "ctest"))
    a = ap.parse_args()
    work = a.work.resolve() / a.recipe
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    t0 = time.monotonic()
    ws, bindir, known = workspace(a.shadowref.resolve(), work)
    {"gitlab": gitlab, "github": github, "bazel": bazel, "ctest": ctest}[a.recipe](ws, bindir, known)
    print(f"{a.recipe}: the recipe ran green, known failures as expected, in {time.monotonic() - t0:.1f} s")


if __name__ == "__main__":
    main()
