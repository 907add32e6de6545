#!/usr/bin/env python3
"""Reviews regenerated golden traces against their previous version (docs/projects.md,
"Golden trace files").

    tools/review_golden.py [--rev REV] PROJECT...

For every scenarios/<name>.toml with a trace, reads expected/<name>.csv as it is in git at
REV (default HEAD) and as it is now, and asserts that the new file says the same as the old
one within the scenario's tolerance:

- the same header;
- every row of the new file is at a time the old file has a row at (the old files have a row
  per base tick), and with `sample = "<duration>"` exactly the old rows at multiples of it;
- with `sample = "change"`: the first and last old rows are there, and every old row equals
  the new row in force at its time (a value holds until the next row), so no change is lost;
- values: numbers within tolerance * max(1, |old|) (REAL rounding), everything else exactly.

Prints one line per scenario and exits 1 if any assertion fails.
"""
import argparse
import csv
import io
import math
import pathlib
import re
import subprocess
import sys
import tomllib

UNITS = {"d": 86400e9, "h": 3600e9, "m": 60e9, "s": 1e9, "ms": 1e6, "us": 1e3, "ns": 1}


def duration_ns(text):
    t = re.sub(r"^(T|TIME|LT|LTIME)#", "", text.strip(), flags=re.I).replace("_", "")
    total = 0
    for num, unit in re.findall(r"(\d+(?:\.\d+)?)(ms|us|ns|d|h|m|s)", t, flags=re.I):
        total += round(float(num) * UNITS[unit.lower()])
    return total


def seconds_ns(text):
    whole, _, frac = text.partition(".")
    return int(whole) * 1_000_000_000 + int((frac + "000000000")[:9])


def read_csv(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], [(seconds_ns(r[0]), r[1:]) for r in rows[1:] if r]


def number(s):
    try:
        return float(s)
    except ValueError:
        return None


def same(old, new, tol):
    if old == new:
        return True
    a, b = number(old), number(new)
    if a is None or b is None:
        return False
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return abs(b - a) <= tol * max(1.0, abs(a))


def review(project, name, rev):
    scen = tomllib.loads((project / "scenarios" / f"{name}.toml").read_text())
    if not scen.get("trace"):
        return None
    tol = float(scen.get("tolerance", 1e-9))
    sample = scen.get("sample")
    rel = (project / "expected" / f"{name}.csv").resolve().relative_to(repo_root())
    shown = subprocess.run(["git", "show", f"{rev}:{rel}"], capture_output=True, text=True, cwd=repo_root())
    if shown.returncode != 0:
        return None   # no golden file at that revision: nothing to review against
    old_text = shown.stdout
    new_text = (project / "expected" / f"{name}.csv").read_text()
    oh, old = read_csv(old_text)
    nh, new = read_csv(new_text)
    problems = []
    if oh != nh:
        problems.append(f"header {nh} != {oh}")
    old_at = {t: v for t, v in old}
    for t, v in new:
        if t not in old_at:
            problems.append(f"row at {t} ns is not in the old file")
            continue
        for col, (a, b) in enumerate(zip(old_at[t], v)):
            if not same(a, b, tol):
                problems.append(f"{nh[col + 1]} at {t / 1e9} s: old {a}, new {b}")
    if sample == "change":
        if not new or new[0][0] != old[0][0] or new[-1][0] != old[-1][0]:
            problems.append("the first or last row is missing")
        k = -1
        for t, v in old:
            while k + 1 < len(new) and new[k + 1][0] <= t:
                k += 1
            for col, (a, b) in enumerate(zip(v, new[k][1])):
                if not same(a, b, tol):
                    problems.append(f"{nh[col + 1]} at {t / 1e9} s: old {a}, held new {b}")
                    break
    elif sample:
        every = duration_ns(sample)
        want = [t for t, _ in old if t % every == 0]
        if [t for t, _ in new] != want:
            problems.append(f"rows are not exactly the old rows at multiples of {sample}")
    elif len(new) != len(old):
        problems.append(f"{len(new)} rows, the old file {len(old)}")
    return len(old), len(new), len(old_text), len(new_text), problems[:10] + (
        [f"... {len(problems) - 10} more"] if len(problems) > 10 else [])


_ROOT = None


def repo_root():
    global _ROOT
    if _ROOT is None:
        _ROOT = pathlib.Path(subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True, text=True,
                                            check=True).stdout.strip())
    return _ROOT


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rev", default="HEAD")
    ap.add_argument("projects", nargs="+", type=pathlib.Path)
    args = ap.parse_args()
    bad = 0
    total_old = total_new = 0
    for project in args.projects:
        for toml in sorted((project / "scenarios").glob("*.toml")):
            r = review(project, toml.stem, args.rev)
            if r is None:
                continue
            old_rows, new_rows, old_bytes, new_bytes, problems = r
            total_old += old_bytes
            total_new += new_bytes
            print(f"{'ok  ' if not problems else 'FAIL'} {project.name}/{toml.stem}: {old_rows} -> {new_rows} rows, "
                  f"{old_bytes} -> {new_bytes} bytes")
            for p in problems:
                print("     " + p)
            bad += bool(problems)
    print(f"{total_old} -> {total_new} bytes; {bad} scenario(s) with problems")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
