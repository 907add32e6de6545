#!/usr/bin/env python3
"""The VCD trace of `stc run --trace ... --trace-out x.vcd`, read back with a small
VCD parser: the header ($date, $version, $timescale), one module scope per program /
GVL / axis / FB instance (nested along the dotted path), enums and STRINGs as string
variables, and the final timestamp at the end of the run.

usage: vcd_test.py STC SOURCE_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

STC, SRC = sys.argv[1], sys.argv[2]
PROJECT = os.path.join(SRC, "tests/cli/vcd_trace")
TRACE = ["AxisX.fSetPosition", "GVL.nCount", "MAIN.eLight", "MAIN.sMsg", "MAIN.blink.q", "MAIN.blink.n"]


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def expect(cond, msg):
    if not cond:
        fail(msg)


def parse_vcd(text):
    """Returns (header {keyword: text}, vars {path: (type, width, id)}, changes {id: [(time, value)]}, times)."""
    tokens = text.split()
    header, scope, vars_, changes, times = {}, [], {}, {}, []
    i, n = 0, len(tokens)
    while i < n:
        tok = tokens[i]
        if tok in ("$date", "$version", "$timescale", "$comment"):
            end = tokens.index("$end", i)
            header[tok[1:]] = " ".join(tokens[i + 1:end])
            i = end + 1
        elif tok == "$scope":
            expect(tokens[i + 1] == "module" and tokens[i + 3] == "$end", f"scope {tokens[i:i + 4]}")
            scope.append(tokens[i + 2])
            i += 4
        elif tok == "$upscope":
            expect(scope, "$upscope without a scope")
            scope.pop()
            i += 2
        elif tok == "$var":
            vtype, width, ident, ref = tokens[i + 1:i + 5]
            expect(tokens[i + 5] == "$end", f"var {tokens[i:i + 6]}")
            vars_[".".join(scope + [ref])] = (vtype, int(width), ident)
            changes[ident] = []
            i += 6
        elif tok == "$enddefinitions":
            expect(not scope, f"scopes left open: {scope}")
            i += 2
        elif tok in ("$dumpvars", "$end"):
            i += 1
        elif tok.startswith("#"):
            t = int(tok[1:])
            expect(not times or t > times[-1], f"time {t} after {times[-1] if times else None}")
            times.append(t)
            i += 1
        elif tok[0] in "bBrRsS":
            expect(tok[1:] or tok[0] in "sS", f"empty vector value at {i}")
            changes[tokens[i + 1]].append((times[-1], tok[1:]))
            i += 2
        elif tok[0] in "01xzXZ":
            changes[tok[1:]].append((times[-1], tok[0]))
            i += 1
        else:
            fail(f"unexpected token {tok!r}")
    return header, vars_, changes, times


def main():
    tmp = tempfile.mkdtemp(prefix="stc-vcd-test-")
    try:
        vcd = os.path.join(tmp, "x.vcd")
        env = dict(os.environ, SOURCE_DATE_EPOCH="86400")
        p = subprocess.run([STC, "run", PROJECT, "--for", "50ms", "--trace", ",".join(TRACE), "--trace-out", vcd],
                           capture_output=True, text=True, env=env)
        expect(p.returncode == 0, f"stc run: {p.returncode} {p.stdout}{p.stderr}")
        text = open(vcd).read()
        header, vars_, changes, times = parse_vcd(text)

        expect(header.get("date") == "1970-01-02 00:00:00 UTC", f"$date {header.get('date')}")
        expect(re.fullmatch(r"stc \d+\.\d+\.\d+", header.get("version", "")), f"$version {header.get('version')}")
        expect(header.get("timescale") == "1ns", f"$timescale {header.get('timescale')}")

        # The scope tree: the dotted paths of the traced names.
        expect(sorted(vars_) == sorted(TRACE), f"variables {sorted(vars_)}")
        scopes = [line.split()[2] for line in text.splitlines() if line.startswith("$scope")]
        expect(scopes == ["AxisX", "GVL", "MAIN", "blink"], f"scopes {scopes}")
        types = {k: v[:2] for k, v in vars_.items()}
        expect(types == {"AxisX.fSetPosition": ("real", 64), "GVL.nCount": ("wire", 32), "MAIN.eLight": ("string", 1),
                         "MAIN.sMsg": ("string", 1), "MAIN.blink.q": ("wire", 1), "MAIN.blink.n": ("wire", 32)},
               f"types {types}")

        # The enum as its value names, changing every 10 cycles.
        light = changes[vars_["MAIN.eLight"][2]]
        expect([v for _, v in light[:4]] == ["Red", "Green", "Yellow", "Red"], f"enum changes {light}")
        expect([t for t, _ in light[:3]] == [0, 9_000_000, 19_000_000], f"enum change times {light}")
        # The STRING as its literal, blanks as $20.
        msg = changes[vars_["MAIN.sMsg"][2]]
        expect(msg == [(0, "'hello$20world'"), (19_000_000, "'bye'")], f"STRING changes {msg}")
        # Only changes are written.
        q = [v for _, v in changes[vars_["MAIN.blink.q"][2]]]
        expect(all(a != b for a, b in zip(q, q[1:])), f"repeated BOOL values {q}")
        # The file ends at the end of the run (50 ms), not at the last change.
        expect(times[-1] == 50_000_000, f"last timestamp {times[-1]}")
        expect(text.rstrip().endswith("#50000000"), "the final timestamp is the last line")

        # --cycles: the end after the last cycle.
        p = subprocess.run([STC, "run", PROJECT, "--cycles", "7", "--trace", "MAIN.sMsg", "--trace-out", vcd],
                           capture_output=True, text=True, env=env)
        expect(p.returncode == 0, f"stc run --cycles: {p.returncode} {p.stderr}")
        _, _, changes, times = parse_vcd(open(vcd).read())
        expect(times == [0, 7_000_000], f"--cycles 7 times {times}")
        print("ok")
    finally:
        shutil.rmtree(tmp, True)


main()
