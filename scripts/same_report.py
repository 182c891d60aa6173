#!/usr/bin/env python3
"""Whether two report.json files give the same verdicts, metrics, causes and resolving power: every
key compared except those that time the run or name where it ran (seconds, frame times, the date,
the host, the command line and the output folders; a reference cache entry's hash, which names the
executable that computed it). Prints the first differences and exits 1 when
there are any, 0 when the two are the same but for those keys, 4 when a file cannot be read.

    scripts/same_report.py before/report.json after/report.json
    scripts/same_report.py --ignore reference_dir --ignore scene_file A B   (two trees, two caches)
"""
import json
import re
import sys

# Keys whose values time the run or say where it ran: never a verdict.
IGNORED = {"seconds", "phase_seconds", "reference_seconds", "frame_ms", "generated", "host", "command",
           "model_seconds"}

# A reference cache entry's folder ends in the hash of its key, the executable's bytes among it.
CACHE_ENTRY = re.compile(r"-[0-9a-f]{16}(?=/|$)")


def strip(value, roots):
    if isinstance(value, dict):
        return {k: strip(v, roots) for k, v in value.items() if k not in IGNORED}
    if isinstance(value, list):
        return [strip(v, roots) for v in value]
    if isinstance(value, str):
        for root, name in roots:
            value = value.replace(root, name)
        value = CACHE_ENTRY.sub("-HASH", value)
    return value


def differences(a, b, path="$"):
    if type(a) is not type(b):
        yield f"{path}: {a!r} against {b!r}"
    elif isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                yield f"{path}.{k}: only in {'the second' if k in b else 'the first'}"
            else:
                yield from differences(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        if len(a) != len(b):
            yield f"{path}: {len(a)} items against {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            yield from differences(x, y, f"{path}[{i}]")
    elif a != b:
        yield f"{path}: {a!r} against {b!r}"


def main():
    args = sys.argv[1:]
    # --ignore KEY: a key more to leave out, e.g. the paths of runs made from two source trees.
    while len(args) >= 2 and args[0] == "--ignore":
        IGNORED.add(args[1])
        args = args[2:]
    if len(args) != 2 or args[0] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if args[:1] in (["-h"], ["--help"]) else 4
    reports = []
    for name in args:
        try:
            with open(name, encoding="utf-8") as f:
                reports.append(json.load(f))
        except (OSError, ValueError) as e:
            print(f"{name}: {e}", file=sys.stderr)
            return 4
    # Each run's own output folder (its report's folder) reads as OUT in both.
    roots = [[(name.rsplit("/report.json", 1)[0], "OUT")] for name in args]
    a, b = (strip(r, root) for r, root in zip(reports, roots))
    found = list(differences(a, b))
    for line in found[:20]:
        print(line)
    if found:
        print(f"{len(found)} difference(s)")
        return 1
    print("the same verdicts, metrics, causes and resolving power")
    return 0


if __name__ == "__main__":
    sys.exit(main())
