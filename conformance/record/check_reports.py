#!/usr/bin/env python3
"""Every report.json that shadowref wrote under the given folders holds to report.json's JSON Schema.

    conformance/record/check_reports.py --schema conformance/record/report.schema.json build/release [MORE...]
    conformance/record/check_reports.py --schema S --at-least 50 build/release     (CTest: the suite's reports)
    conformance/record/check_reports.py --schema S run-a/report.json               (one file)

A folder is walked for files named report.json that `shadowref conform` or `shadowref merge` wrote:
those with summary.md beside them (both commands write it, and report.json only after it). A
report.json with no summary.md beside it is a test's hand-written bad input (reliability/bad_input_test.cpp
writes such files to see `merge` and `diff` refuse them) and is left alone. A file named on the command
line is always checked.

Each problem is one line, `<file>: <JSON path>: <what is wrong>` (`cases[3].status`, as
shadowref's own messages write a path). Before the walk, the teeth: the
first report with a judged case is broken in each of the ways the schema must see (a missing key, a
status outside the table, a key of the wrong type, a key no writer writes, a count that is a float),
and each broken copy must be refused at the path it was broken at. A schema that passed any of
them would pass a wrong writer.

Reads each report through report_record.py beside it, the Python side of the record library.
Exit 0 when every report holds and the teeth bite; 1 when a report does not hold, a tooth does not
bite or fewer than --at-least reports were found; 4 when the schema or a named file cannot be read.
"""
import argparse
import copy
import json
import pathlib
import sys

try:
    from report_record import ReportError, problems, validator
except ImportError:  # pragma: no cover - set-up installs python3-jsonschema
    print("check_reports.py: python3-jsonschema is not installed (bash scripts/setup.sh installs it)", file=sys.stderr)
    sys.exit(4)


def shadowref_reports(folder):
    """The report.json files under `folder` that conform or merge wrote (summary.md beside each)."""
    return sorted(p for p in folder.rglob("report.json") if (p.parent / "summary.md").is_file())


# The ways a wrong writer could break a judged case, each with the path the schema must name.
def mutants(report):
    index = next((i for i, c in enumerate(report.get("cases", [])) if "comparison" in c), None)
    if index is None:
        return []

    def case_broken(what, change, at):
        r = copy.deepcopy(report)
        change(r["cases"][index])
        return what, r, f"cases[{index}]{at}"

    return [
        case_broken("no scene", lambda c: c.pop("scene"), ""),
        case_broken("a status outside the table", lambda c: c.update(status="MAYBE"), ".status"),
        case_broken("seconds as text", lambda c: c.update(seconds="1.5"), ".seconds"),
        case_broken("a key no writer writes", lambda c: c.update(verdict_of_the_day="PASS"), ""),
        case_broken("a float where a count goes", lambda c: c["comparison"]["total"].update(wrong=1.5),
                    ".comparison.total.wrong"),
        case_broken("an outcome outside the table", lambda c: c.update(expectation={"outcome": "lucky"}),
                    ".expectation.outcome"),
    ]


def teeth(v, report, where):
    """Lines naming each broken copy of `report` the schema let through or refused elsewhere."""
    out = []
    found = mutants(report)
    if not found:
        return [f"{where}: no judged case to break (the teeth need one)"]
    for what, broken, at in found:
        paths = [p for p, _ in problems(v, broken)]
        if at not in paths:
            out.append(f"{where}: the schema does not refuse {what} at {at} (it said: {paths or 'nothing'})")
    return out


def read_json(path):
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as e:
        raise SystemExit(f"check_reports.py: {path}: cannot read it ({e})")
    except json.JSONDecodeError as e:
        return e


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--schema", type=pathlib.Path, required=True, help="report.schema.json")
    ap.add_argument("--at-least", type=int, default=1, metavar="N", help="fail when fewer reports are found (default 1)")
    ap.add_argument("paths", nargs="+", type=pathlib.Path, help="folders to walk, or report.json files")
    a = ap.parse_args()

    try:
        v = validator(a.schema)
    except ReportError as e:
        print(f"check_reports.py: {e}", file=sys.stderr)
        return 4

    files = []
    for p in a.paths:
        if p.is_dir():
            files += shadowref_reports(p)
        elif p.is_file():
            files.append(p)
        else:
            print(f"check_reports.py: {p}: no such file or folder", file=sys.stderr)
            return 4

    bad = []
    toothless = None
    for f in files:
        report = read_json(f)
        if isinstance(report, json.JSONDecodeError):
            bad.append(f"{f}: not JSON ({report})")
            continue
        bad += [f"{f}: {path}: {message}" for path, message in problems(v, report)]
        if toothless is None and any("comparison" in c for c in report.get("cases", []) if isinstance(c, dict)):
            toothless = teeth(v, report, f)
    for line in bad + (toothless or []):
        print(line, file=sys.stderr)
    if len(files) < a.at_least:
        print(f"check_reports.py: {len(files)} report.json found, fewer than the {a.at_least} asked for "
              "(run the tests that write them first)", file=sys.stderr)
        return 1
    if toothless is None:
        print("check_reports.py: no report with a judged case, so the teeth were not tried", file=sys.stderr)
        return 1
    if bad or toothless:
        return 1
    print(f"{len(files)} report.json hold to {a.schema.name}; every broken copy of one is refused where it was broken")
    return 0


if __name__ == "__main__":
    sys.exit(main())
