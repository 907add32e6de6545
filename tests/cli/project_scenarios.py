#!/usr/bin/env python3
"""Checks example projects until `stc test` exists: `stc check --Werror` must be clean, and
every scenario without stimuli ([[set]], [[fault]]) runs through `stc run --trace-out` with its
[[check]] tables evaluated on the trace (docs/projects.md).  Scenarios with stimuli are only
compiled (their checks need `stc test`).  Usage: project_scenarios.py STC PROJECTDIR..."""
import csv, os, re, subprocess, sys, tempfile, tomllib

UNITS = {"ms": 1e-3, "s": 1.0, "us": 1e-6, "m": 60.0, "h": 3600.0}


def seconds(text):
    total, rest = 0.0, text.strip().lower().removeprefix("t#").removeprefix("time#")
    for num, unit in re.findall(r"([0-9.]+)(ms|us|s|m|h)", rest):
        total += float(num) * UNITS[unit]
    if not rest or re.sub(r"([0-9.]+)(ms|us|s|m|h)", "", rest).replace("_", ""):
        raise ValueError(f"not a duration: {text}")
    return total


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def same(actual, expected, tol):
    a, e = number(actual), number(expected)
    if a is not None and e is not None:
        return abs(a - e) <= tol * max(1.0, abs(e))
    norm = lambda s: s.strip().upper().replace(".", "#")
    return norm(actual) == norm(expected)


def run_scenario(stc, project, path, failures):
    sc = tomllib.load(open(path, "rb"))
    name = f"{os.path.basename(project)}/{os.path.basename(path)}"
    checks = sc.get("check", [])
    if not checks:
        failures.append(f"{name}: no [[check]]")
    if sc.get("set") or sc.get("fault"):
        print(f"SKIP {name}: stimuli need stc test")
        return
    cols = list(dict.fromkeys(sc.get("trace", []) + [c["var"] for c in checks]))
    tol = float(sc.get("tolerance", 1e-9))
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "t.csv")
        cmd = [stc, "run", project, "--trace", ",".join(cols), "--trace-out", out]
        cmd += ["--cycles", str(sc["cycles"])] if "cycles" in sc else ["--for", sc["duration"]]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            failures.append(f"{name}: stc run exit {r.returncode}: {r.stdout}{r.stderr}")
            return
        rows = list(csv.DictReader(open(out)))
    times = [float(row["time"]) for row in rows]
    for c in checks:
        var, col = c["var"], [row[c["var"]] for row in rows]
        if "equals" in c:
            t = seconds(c["at"])
            idx = max((i for i, x in enumerate(times) if x <= t + 1e-9), default=None)
            if idx is None or not same(col[idx], c["equals"], tol):
                got = None if idx is None else col[idx]
                failures.append(f"{name}: {var} at {c['at']}: expected {c['equals']}, got {got}")
        elif "rises_between" in c:
            lo, hi = (seconds(x) for x in c["rises_between"])
            ok = any(col[i - 1].upper() == "FALSE" and col[i].upper() == "TRUE" and
                     lo - 1e-9 <= times[i] <= hi + 1e-9 for i in range(1, len(col)))
            if not ok:
                failures.append(f"{name}: {var} does not rise in [{lo}, {hi}]")
        else:
            vals = [float(v) for v in col]
            if "min" in c and min(vals) < c["min"] - tol * max(1.0, abs(c["min"])):
                failures.append(f"{name}: {var} min {min(vals)} < {c['min']}")
            if "max" in c and max(vals) > c["max"] + tol * max(1.0, abs(c["max"])):
                failures.append(f"{name}: {var} max {max(vals)} > {c['max']}")
    print(f"RAN  {name}: {len(checks)} checks")


def main():
    stc, projects = sys.argv[1], sys.argv[2:]
    failures = []
    for project in projects:
        r = subprocess.run([stc, "check", "--Werror", project], capture_output=True, text=True)
        if r.returncode != 0 or r.stdout.strip() or r.stderr.strip():
            failures.append(f"{project}: stc check: {r.stdout}{r.stderr}")
        scen = os.path.join(project, "scenarios")
        files = sorted(f for f in os.listdir(scen) if f.endswith(".toml")) if os.path.isdir(scen) else []
        if not files:
            failures.append(f"{project}: no scenarios")
        for f in files:
            run_scenario(stc, project, os.path.join(scen, f), failures)
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
