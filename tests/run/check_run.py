#!/usr/bin/env python3
"""Runs one tests/run/*.st file through `stc run` and checks the result.

Header comments in the file:
  // stc-run: ARGS            arguments after the file name (may repeat; joined)
  // expect: LINE             stdout must consist of exactly these lines, in order
  // expect-exit: N           exit status (default 0)
  // expect-stderr: TEXT      stderr must contain TEXT ({{FILE}} = the file's path)
  // run-twice-identical: F   run twice writing trace F (in a temp dir); the files must be byte-identical
"""
import os
import shlex
import subprocess
import sys
import tempfile


def main():
    # check_run.py STC FILE [TARGET]: headers from FILE; runs TARGET (a project
    # directory, say) instead of FILE when given.
    stc, path = sys.argv[1], sys.argv[2]
    target = sys.argv[3] if len(sys.argv) > 3 else path
    args, expect, stderr_expect = [], [], []
    exit_code = 0
    twice = None
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            s = line.strip()
            if s.startswith("// stc-run:"):
                args += shlex.split(s[len("// stc-run:"):])
            elif s.startswith("// expect:"):
                expect.append(s[len("// expect:"):].strip())
            elif s.startswith("// expect-exit:"):
                exit_code = int(s[len("// expect-exit:"):])
            elif s.startswith("// expect-stderr:"):
                stderr_expect.append(s[len("// expect-stderr:"):].strip().replace("{{FILE}}", path))
            elif s.startswith("// run-twice-identical:"):
                twice = s[len("// run-twice-identical:"):].strip()
    with tempfile.TemporaryDirectory() as tmp:
        run_args = [a.replace("{{TMP}}", tmp) for a in args]
        cmd = [stc, "run", target, "--color=never"] + run_args
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        ok = True
        got = [l for l in p.stdout.splitlines()]
        if got != expect:
            print("stdout mismatch\n--- expected\n" + "\n".join(expect) + "\n--- got\n" + "\n".join(got))
            ok = False
        if p.returncode != exit_code:
            print(f"exit status {p.returncode}, expected {exit_code}")
            ok = False
        for e in stderr_expect:
            if e not in p.stderr:
                print(f"stderr lacks: {e}")
                ok = False
        if twice:
            first = open(os.path.join(tmp, twice), "rb").read()
            p2 = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
            second = open(os.path.join(tmp, twice), "rb").read()
            if first != second or p2.stdout != p.stdout:
                print("second run differs")
                ok = False
        if not ok:
            print("command: " + " ".join(shlex.quote(c) for c in cmd))
            print("stderr:\n" + p.stderr)
            sys.exit(1)


if __name__ == "__main__":
    main()
