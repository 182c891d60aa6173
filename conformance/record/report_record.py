"""conformance/record/report_record.py — report.json read in Python as the record library reads it in C++.

The Python readers of a run (engines/run_engines.py, check_reports.py) take a report through here:
the file is parsed and held to report.schema.json beside this file (the schema the C++ writer is
tested against), and only then are its cases read, so that a reader never acts on a key the writer
did not write or on a value of the wrong type. One problem is one line, `<file>: <JSON path>:
<what is wrong>`, the path written as shadowref's own messages write one (`cases[3].status`).

Uses python3-jsonschema (Debian 12: 4.10.3, which has Draft 2020-12; scripts/setup.sh installs it).
"""
import json
import pathlib

from jsonschema import Draft202012Validator

SCHEMA = pathlib.Path(__file__).with_name("report.schema.json")


class ReportError(ValueError):
    """A report.json that cannot be read or does not hold to the schema: its first problem, one line."""


def json_path(error):
    """`cases[3].status` for a jsonschema error; `$` for the report itself."""
    out = ""
    for part in error.absolute_path:
        out += f"[{part}]" if isinstance(part, int) else f".{part}" if out else str(part)
    return out or "$"


def validator(schema_file=SCHEMA):
    """A Draft 2020-12 validator of report.json; raises ReportError when the schema is not one."""
    try:
        schema = json.loads(pathlib.Path(schema_file).read_text(encoding="utf-8"))
        Draft202012Validator.check_schema(schema)
    except (OSError, ValueError) as e:
        raise ReportError(f"{schema_file}: not a readable JSON Schema ({e})") from e
    except Exception as e:  # jsonschema's SchemaError: the schema itself is wrong
        raise ReportError(f"{schema_file}: {getattr(e, 'message', e)}") from e
    return Draft202012Validator(schema)


def problems(v, report):
    """[(JSON path, message)] of `report` against validator `v`, in document order."""
    return [(json_path(e), e.message) for e in v.iter_errors(report)]


def read_report(path, v=None):
    """The report.json at `path` as a dict that holds to the schema (ReportError otherwise)."""
    path = pathlib.Path(path)
    try:
        report = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
        raise ReportError(f"{path}: cannot read it as JSON ({e})") from e
    found = problems(v or validator(), report)
    if found:
        at, message = found[0]
        raise ReportError(f"{path}: {at}: {message}")
    return report


def case_statuses(report):
    """{scene: status} of a report read by read_report (one technique per run, as the engines' are)."""
    return {c["scene"]: c["status"] for c in report["cases"]}
