#!/usr/bin/env python3
"""Golden test of the exact text (and JSON) rendering of diagnostics.

Usage: check_render.py STC FILE.st

Runs the compiler the way a user would, from the repository root with a
relative path, so that the file names in the output are stable:

    cd <repo root> && STC check --color=never tests/diagnostics/render/FILE.st

Convention for the expected output, next to FILE.st:
  * FILE.json.expected  if it exists: the run adds --format=json and its
                        *stdout* must equal this file (stderr is ignored);
  * FILE.expected       otherwise: the run's *stderr* (clang-style text,
                        including the final "N errors generated." line) must
                        equal this file.
Exactly one of the two must exist.  The exit status must be 0 or 1 (2 is a
command-line error, anything else a crash).

Exit status: 0 when the output matches, 1 with a unified diff when it does
not (or when the compiler crashed), 2 on bad usage.
"""
import difflib
import os
import subprocess
import sys


def main():
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    stc = os.path.abspath(sys.argv[1])
    src = os.path.abspath(sys.argv[2])
    root = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))
    rel = os.path.relpath(src, root)
    if rel.startswith(".."):
        print(f"check_render: {src} is not inside the repository {root}", file=sys.stderr)
        return 2
    base = src[:-3] if src.endswith(".st") else src
    json_expected = base + ".json.expected"
    text_expected = base + ".expected"
    is_json = os.path.exists(json_expected)
    expected_path = json_expected if is_json else text_expected
    if not os.path.exists(expected_path):
        print(f"check_render: neither {text_expected} nor {json_expected} exists", file=sys.stderr)
        return 2

    cmd = [stc, "check", "--color=never"] + (["--format=json"] if is_json else []) + [rel]
    proc = subprocess.run(cmd, cwd=root, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    actual = (proc.stdout if is_json else proc.stderr).decode("utf-8", errors="replace")
    with open(expected_path, encoding="utf-8") as f:
        expected = f.read()

    ok = True
    if proc.returncode not in (0, 1):
        print(f"check_render: '{' '.join(cmd)}' exited with status {proc.returncode}", file=sys.stderr)
        ok = False
    if actual != expected:
        print(f"check_render: output of '{' '.join(cmd)}' (cwd {root}) differs from {os.path.relpath(expected_path, root)}:")
        sys.stdout.writelines(difflib.unified_diff(
            expected.splitlines(keepends=True), actual.splitlines(keepends=True),
            fromfile=os.path.relpath(expected_path, root), tofile="actual output"))
        if not actual.endswith("\n") or not expected.endswith("\n"):
            print("\n(note: one of the two has no final newline)")
        ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
