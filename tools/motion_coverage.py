#!/usr/bin/env python3
"""Regenerates the instruction coverage tables of docs/motion.md (single-axis rows)
and docs/motion-groups.md (axis-group, interpolation and kinematics rows) from the
spec CSVs.

For every such row it prints whether the instruction is declared in
stdlib-motion/**/*.st and which test files (tests/**, projects/**) exercise it,
and rewrites the table between the markers <!-- coverage:begin --> and
<!-- coverage:end --> of each page.

    python3 tools/motion_coverage.py [--spec-dir ../shared/spec] [--check]

--check exits 1 when a table in the docs is out of date (nothing is written).
"""
import argparse
import csv
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# (page, what its rows are, instruction set -> which categories)
TABLES = [
    ("docs/motion.md", "single-axis", {
        "amc1600c": lambda c: not c.startswith("Synchronized motion"),
        "leadshine_pmc600": lambda c: c.startswith("Single-axis"),
    }),
    ("docs/motion-groups.md", "axis-group, interpolation and kinematics", {
        "leadshine_pmc600": lambda c: c.startswith("Axis group") or c.startswith("Leadshine interpolation"),
        "moons_cnc": lambda c: c == "kinematics",
    }),
]
BEGIN, END = "<!-- coverage:begin -->", "<!-- coverage:end -->"


def declared(root):
    names = {}
    decl = re.compile(r"^\s*(?:FUNCTION_BLOCK|FUNCTION)\s+([A-Za-z_]\w*)", re.M | re.I)
    action = re.compile(r"^\s*ACTION\s+([A-Za-z_]\w*)", re.M | re.I)
    for dirpath, _, files in os.walk(os.path.join(root, "stdlib-motion")):
        for f in sorted(files):
            if not f.endswith(".st"):
                continue
            path = os.path.join(dirpath, f)
            text = open(path, encoding="utf-8", errors="replace").read()
            rel = os.path.relpath(path, root)
            fbs = decl.findall(text)
            for n in fbs:
                names.setdefault(n.lower(), rel)
            for a in action.findall(text):
                for n in fbs:
                    names.setdefault(f"{n}.{a}".lower(), rel)
    return names


def test_files(root):
    out = []
    for sub in ("tests", "projects"):
        for dirpath, _, files in os.walk(os.path.join(root, sub)):
            # The parser corpus only names instructions (stub declarations); it does not run them.
            if os.path.relpath(dirpath, root).startswith(os.path.join("tests", "corpus")):
                continue
            for f in sorted(files):
                if f.endswith((".st", ".cpp", ".expect", ".toml")):
                    path = os.path.join(dirpath, f)
                    words = set(w.lower() for w in re.findall(r"[A-Za-z_]\w*(?:\.[A-Za-z_]\w*)?", open(path, encoding="utf-8", errors="replace").read()))
                    words |= set(w.lower() for w in re.findall(r"[A-Za-z_]\w*", open(path, encoding="utf-8", errors="replace").read()))
                    rel = os.path.relpath(path, root)
                    # run-projects/<name>/...: the project names the test.
                    m = re.match(r"tests/run-projects/([^/]+)/", rel)
                    out.append((m.group(1) + "/" if m else os.path.basename(rel), words))
    return out


def table(spec_dir, sets, what, decl, tests):
    lines = ["| set | instruction | category | declared in | tested by |", "| --- | --- | --- | --- | --- |"]
    done = total = 0
    for vendor, single in sets.items():
        with open(os.path.join(spec_dir, f"{vendor}.csv"), encoding="utf-8") as f:
            for row in csv.DictReader(f):
                if not single(row["category"]):
                    continue
                name = row["name"]
                total += 1
                where = decl.get(name.lower(), "")
                # An action (FB.Action) is exercised where the FB and a call of the action appear.
                parts = name.lower().split(".")
                used = sorted(set(p for p, words in tests if all(w in words for w in parts)))
                ok = bool(where) and bool(used)
                done += ok
                shown = ", ".join(used[:4]) + (f" (+{len(used) - 4})" if len(used) > 4 else "")
                lines.append(f"| {vendor} | {name} | {row['category']} | {os.path.basename(where) if where else '**missing**'} | {shown or '**none**'} |")
    lines.append("")
    lines.append(f"{done} of {total} {what} rows declared and tested.")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spec-dir", default=os.path.join(ROOT, "..", "shared", "spec"))
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    decl, tests = declared(ROOT), test_files(ROOT)
    stale = False
    for page, what, sets in TABLES:
        doc = os.path.join(ROOT, page)
        text = open(doc, encoding="utf-8").read()
        if BEGIN not in text or END not in text:
            sys.exit(f"{doc}: markers {BEGIN} / {END} not found")
        new = text[: text.index(BEGIN) + len(BEGIN)] + "\n" + table(a.spec_dir, sets, what, decl, tests) + "\n" + text[text.index(END):]
        stale = stale or new != text
        if not a.check and new != text:
            open(doc, "w", encoding="utf-8").write(new)
        print(new[new.index(BEGIN): new.index(END)].splitlines()[-1])
    if a.check:
        sys.exit(1 if stale else 0)


if __name__ == "__main__":
    main()
