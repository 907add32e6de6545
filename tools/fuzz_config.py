#!/usr/bin/env python3
"""Mutation fuzzer for project.toml and scenarios/*.toml (issue 14, items 4 and 6).

Copies an example project, mutates its project.toml and scenario files (hostile values:
NaN, Inf, negative limits, bad and overflowing durations, injection text, typos in keys,
duplicated, dropped or truncated lines, random bytes ...; now and then a file replaced by a
FIFO, a directory, a symbolic-link loop or /dev/zero) and runs `stc check` and `stc test`
on it.  Any signal, abort, sanitizer report, crashed child or timeout is a
failure: the mutated project is kept under OUT/crash-N/ and the exit status is 1.
Exit statuses 0, 1 and 2 are fine (the input may be valid or refused).

usage: tools/fuzz_config.py SECONDS [--stc build/stc] [--seed N] [--out DIR] [PROJECT...]
(default projects: every projects/*/ with scenarios and tests/test-projects/axis_demo)
"""
import argparse
import os
import random
import re
import shutil
import stat
import subprocess
import sys
import tempfile
import time

try:
    import tomllib
except ImportError:  # Python < 3.11: no pre-filter of long runs (timeouts still count)
    tomllib = None

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

HOSTILE = [
    "nan", "+nan", "-nan", "inf", "-inf", "+inf", "-1", "0", "-0.0", "1e308", "-1e308", "1e-320",
    "9223372036854775807", "-9223372036854775808", "18446744073709551616", "99999999999999999999",
    "true", "false", "[]", "[1.0]", "[nan, 1.0]", "[1.0, -1.0]", "[[1.0]]", "{}", "{ x = 1 }",
    '""', '" "', '".s"', '"1.2.3s"', '"99999999999999h"', '"T#"', '"-5ms"', '"0s"', '"1ns"', '"1e3ms"',
    '"1h30m"', '"T#1h_30m"', '"' + "9" * 5000 + 'ms"', '"' + "1" * 300 + '"',
    '"1ms, PRIORITY := 3); TASK Evil(INTERVAL := T#1ms"', '"MAIN; END_RESOURCE"', '"GVL.x); (*"',
    '"NaN"', '"Inf"', '"-1.0E+400"', '"16#FFFFFFFFFFFFFFFFFF"', '"TRUE"', '"E_State#Nope"', "'''\n'''",
    '"\\u0000"', '"\u00e9\u00e8"', '"' + "x" * 10000 + '"', "1979-05-27T07:32:00Z", "0x7fffffff", "1_000", "-1_0.5e3",
]
KEYS = ["max_velocty", "name", "nmae", "period", "kv", "duration", "cycles", "var", "at", "equals", "min", "max",
        "tolerance", "interval", "event", "priority", "programs", "task", "window", "delay", "rises_between",
        "libraries", "dialect", "address_model", "trace", "value", "kind", "axis", "x" * 200, "a.b.c", '"quoted key"']
TABLES = ["[[axis]]", "[[task]]", "[[io]]", "[[cam]]", "[[check]]", "[[set]]", "[[fault]]", "[[axis.fault]]",
          "[project]", "[build]", "[projet]", "[[axis]]\nname = \"Axis1\"", "[[task]]\nname = \"T\"\ninterval = \"1ms\"\nprograms = [\"MAIN\"]"]


def mutate(text, rng):
    lines = text.split("\n")
    kv = [i for i, l in enumerate(lines) if re.match(r"\s*[A-Za-z_][A-Za-z0-9_.]*\s*=", l)]
    op = rng.randrange(13)
    if op <= 3 and kv:                       # a hostile value
        i = rng.choice(kv)
        key = lines[i].split("=", 1)[0]
        lines[i] = key + "= " + rng.choice(HOSTILE)
    elif op == 4 and kv:                     # another line's value
        i, j = rng.choice(kv), rng.choice(kv)
        lines[i] = lines[i].split("=", 1)[0] + "=" + lines[j].split("=", 1)[1]
    elif op == 5 and kv:                     # a typo in a key
        i = rng.choice(kv)
        key, val = lines[i].split("=", 1)
        k = list(key.strip())
        p = rng.randrange(len(k))
        r = rng.randrange(3)
        if r == 0 and len(k) > 1: del k[p]
        elif r == 1: k.insert(p, rng.choice("abcdefghijklmnopqrstuvwxyz_"))
        elif p + 1 < len(k): k[p], k[p + 1] = k[p + 1], k[p]
        lines[i] = "".join(k) + " =" + val
    elif op == 6:                            # a new key
        lines.insert(rng.randrange(len(lines) + 1), rng.choice(KEYS) + " = " + rng.choice(HOSTILE))
    elif op == 7 and lines:                  # drop / duplicate / swap lines
        i = rng.randrange(len(lines))
        r = rng.randrange(3)
        if r == 0: del lines[i]
        elif r == 1: lines.insert(i, lines[i])
        else:
            j = rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
    elif op == 8:                            # a table header
        lines.insert(rng.randrange(len(lines) + 1), rng.choice(TABLES))
    elif op == 9 and lines:                  # a [[table]] block repeated many times
        heads = [i for i, l in enumerate(lines) if l.startswith("[[")] or [0]
        s = rng.choice(heads)
        e = next((k for k in range(s + 1, len(lines)) if lines[k].startswith("[")), len(lines))
        lines += lines[s:e] * rng.choice([2, 10, 1000])
    elif op == 10:                           # truncated
        text = "\n".join(lines)
        return text[: rng.randrange(len(text) + 1)]
    elif op == 11:                           # random bytes
        b = bytearray("\n".join(lines).encode("utf-8", "surrogateescape"))
        for _ in range(rng.randrange(1, 8)):
            if b and rng.random() < 0.5: b[rng.randrange(len(b))] = rng.randrange(256)
            else: b.insert(rng.randrange(len(b) + 1), rng.randrange(256))
        return b.decode("utf-8", "surrogateescape")
    else:                                    # numbers nudged: digits changed in place
        text = "\n".join(lines)
        nums = list(re.finditer(r"\d+", text))
        if nums:
            m = rng.choice(nums)
            return text[: m.start()] + rng.choice(["0", "1", "-1", "999999", "1" * 25]) + text[m.end():]
    return "\n".join(lines)


def replace_by_special(proj, rng):
    """A file the tools read replaced by a FIFO, a directory, a symbolic-link loop or a device:
    a clear error, never a hang (the per-command timeout catches one)."""
    cands = [os.path.join(proj, "project.toml")]
    for sub in ("scenarios", "expected", "src"):
        d = os.path.join(proj, sub)
        if os.path.isdir(d):
            cands += [os.path.join(d, f) for f in os.listdir(d)]
    f = rng.choice(cands)
    if os.path.isdir(f) and not os.path.islink(f):
        shutil.rmtree(f)
    elif os.path.lexists(f):
        os.remove(f)
    kind = rng.randrange(4)
    if kind == 0: os.mkfifo(f)
    elif kind == 1: os.mkdir(f)
    elif kind == 2: os.symlink(os.path.basename(f), f)
    else: os.symlink("/dev/zero", f)


UNITS = {"d": 86400.0, "h": 3600.0, "m": 60.0, "s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}


def seconds(text):
    t = re.sub(r"^(?i:ltime#|time#|lt#|t#)", "", str(text).replace("_", ""))
    parts = re.findall(r"([0-9.]+)([a-zA-Z]+)", t)
    try:
        return sum(float(n) * UNITS.get(u.lower(), 0.0) for n, u in parts)
    except ValueError:
        return 0.0


def too_long(project):
    """A valid but long simulation (a mutated duration of hours, a 1 ns task): stc is right
    to run it, but it would take minutes, so only `stc check` is run on such inputs."""
    if tomllib is None:
        return False
    regular = lambda p: os.path.isfile(p) and not stat.S_ISFIFO(os.stat(p).st_mode)
    try:
        if not regular(os.path.join(project, "project.toml")):
            return False
        with open(os.path.join(project, "project.toml"), "rb") as f:
            cfg = tomllib.load(f)
        for t in cfg.get("task", []) if isinstance(cfg.get("task"), list) else []:
            if isinstance(t, dict) and isinstance(t.get("interval"), str) and 0 < seconds(t["interval"]) < 1e-4:
                return True
        for name in os.listdir(os.path.join(project, "scenarios")):
            if not regular(os.path.join(project, "scenarios", name)):
                continue
            with open(os.path.join(project, "scenarios", name), "rb") as f:
                sc = tomllib.load(f)
            d, c = sc.get("duration"), sc.get("cycles")
            if (isinstance(d, str) and seconds(d) > 30) or (isinstance(c, int) and c > 30000):
                return True
            for tab in ("set", "check", "fault"):
                for x in sc.get(tab, []) if isinstance(sc.get(tab), list) else []:
                    if isinstance(x, dict) and isinstance(x.get("at"), str) and seconds(x["at"]) > 30:
                        return True
    except Exception:
        return False    # stc refuses what tomllib cannot read: fast
    return False


BAD_OUTPUT = re.compile(r"AddressSanitizer|UndefinedBehaviorSanitizer|runtime error:|terminate called|Assertion .* failed|"
                        r"the test process died|the test process exited with status")


def run(cmd, timeout):
    # A process group of its own: on a timeout the whole group goes (stc test's children
    # hold the output pipe too).
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        out, _ = p.communicate(timeout=timeout)
        return p.returncode, out.decode("utf-8", "replace")
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, 9)
        out, _ = p.communicate()
        return "timeout", out.decode("utf-8", "replace")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("seconds", type=float)
    ap.add_argument("--stc", default=os.path.join(ROOT, "build", "stc"))
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "fuzz-config"))
    ap.add_argument("--timeout", type=float, default=30.0, help="seconds one stc command may take")
    ap.add_argument("projects", nargs="*")
    a = ap.parse_args()
    seed = a.seed if a.seed is not None else random.randrange(1 << 30)
    rng = random.Random(seed)
    projects = a.projects or sorted(
        [os.path.join(ROOT, "projects", d) for d in os.listdir(os.path.join(ROOT, "projects"))
         if os.path.isdir(os.path.join(ROOT, "projects", d, "scenarios"))] +
        [os.path.join(ROOT, "tests", "test-projects", "axis_demo")])
    print(f"fuzz_config: seed {seed}, {len(projects)} projects, {a.seconds:g} s, stc {a.stc}", flush=True)
    end = time.monotonic() + a.seconds
    stats = {}
    failures = 0
    runs = 0
    work = tempfile.mkdtemp(prefix="stc-fuzz-config-")
    try:
        while time.monotonic() < end:
            src = rng.choice(projects)
            proj = os.path.join(work, os.path.basename(src.rstrip("/")))
            shutil.rmtree(proj, ignore_errors=True)
            shutil.copytree(src, proj, symlinks=True)
            files = [os.path.join(proj, "project.toml")]
            sd = os.path.join(proj, "scenarios")
            if os.path.isdir(sd):
                files += [os.path.join(sd, f) for f in sorted(os.listdir(sd)) if f.endswith(".toml")]
            for _ in range(rng.choice([1, 1, 2, 3, 5])):
                f = rng.choice(files)
                with open(f, encoding="utf-8", errors="surrogateescape") as h:
                    text = h.read()
                with open(f, "w", encoding="utf-8", errors="surrogateescape") as h:
                    h.write(mutate(text, rng))
            if rng.random() < 0.05:
                replace_by_special(proj, rng)
            cmds = [[a.stc, "check", proj]]
            if not too_long(proj):
                cmds.append([a.stc, "test", "-j", "1", proj])
            for cmd in cmds:
                rc, out = run(cmd, a.timeout)
                runs += 1
                stats[(cmd[1], rc)] = stats.get((cmd[1], rc), 0) + 1
                bad = rc == "timeout" or rc not in (0, 1, 2) or BAD_OUTPUT.search(out)
                if bad:
                    failures += 1
                    keep = os.path.join(a.out, f"crash-{seed}-{failures}")
                    shutil.rmtree(keep, ignore_errors=True)
                    os.makedirs(a.out, exist_ok=True)
                    shutil.copytree(proj, keep, symlinks=True)
                    with open(os.path.join(keep, "FUZZ-REPORT.txt"), "w") as h:
                        h.write(f"command: {' '.join(cmd)}\nexit: {rc}\n\n{out}")
                    print(f"FAILURE ({rc}): {' '.join(cmd[:2])} on a mutated {os.path.basename(src)}; kept in {keep}")
                    print("\n".join(out.splitlines()[-15:]), flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    summary = ", ".join(f"{c} exit {rc}: {n}" for (c, rc), n in sorted(stats.items(), key=lambda x: (x[0][0], str(x[0][1]))))
    print(f"fuzz_config: {runs} runs ({summary}); {failures} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
