#!/usr/bin/python3
"""Compares two recordings of the CLI suites' runs (ROVING_CLI_RECORD=DIR, tests/cli_support.h) byte for
byte, times, process ids and the tool's commit apart: a refactoring that must not change a report
records before and after and runs

    python3 tests/compare_reports.py BEFORE AFTER

It prints each run that differs with a unified diff of the two, and exits 1 if any does (or if a run
is in one recording only)."""
import difflib
import pathlib
import re
import sys

# What may differ between two runs of the same command: elapsed times (text "0.072 s", rates
# "3.89e+05 samples/s", JSON "seconds" objects and *_seconds fields), the scratch folders' process
# ids, and the build's commit.
VOLATILE = [
    (re.compile(r"(roving-[a-z-]*[a-z])-\d+"), r"\1-PID"),
    (re.compile(r"\d+(\.\d+)?(e[+-]?\d+)? s\b"), "T s"),
    (re.compile(r"(time: load T s \((A|reference) )[\d.]+(, (B|test) )[\d.]+"), r"\1T\3T"),
    (re.compile(r"[\d.e+-]+ samples/s"), "R samples/s"),
    (re.compile(r'("[a-z_]*seconds[a-z_]*": *)[\d.e+-]+'), r"\1T"),
    (re.compile(r'"seconds": *\{[^{}]*\}'), '"seconds": {T}'),
    (re.compile(r'"commit": *"[0-9a-f]*(-dirty)?"'), '"commit": "C"'),
    (re.compile(r"\(commit [0-9a-f]+(-dirty)?\)"), "(commit C)"),
]


# Runs whose output is not deterministic by design: the batch killed at random moments (its resumed
# result is compared within the test; how many pairs each kill left done is chance). And a shard
# part's size, which counts its description's bytes, the tool's commit among them.
SKIPPED = re.compile(r"^CrashConsistency\.BatchKilledAtRandomMoments")
VOLATILE.append((re.compile(r"expected \d+ bytes \(the description, then (\d+) bytes per sample\), found \d+"),
                 r"expected N bytes (the description, then \1 bytes per sample), found M"))


def normalised(text):
    for pattern, replacement in VOLATILE:
        text = pattern.sub(replacement, text)
    return text


def main(before, after):
    before, after = pathlib.Path(before), pathlib.Path(after)
    names = sorted({p.name for p in before.iterdir()} | {p.name for p in after.iterdir()})
    names = [name for name in names if not SKIPPED.match(name)]
    differing = 0
    for name in names:
        old, new = before / name, after / name
        if not old.exists() or not new.exists():
            print(f"{name}: only in {'AFTER' if not old.exists() else 'BEFORE'}")
            differing += 1
            continue
        a = normalised(old.read_text(errors="replace")).splitlines(keepends=True)
        b = normalised(new.read_text(errors="replace")).splitlines(keepends=True)
        if a != b:
            differing += 1
            sys.stdout.writelines(difflib.unified_diff(a, b, f"BEFORE/{name}", f"AFTER/{name}", n=1))
    print(f"{len(names)} runs, {differing} differing")
    return 1 if differing else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
