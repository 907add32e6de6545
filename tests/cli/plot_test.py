#!/usr/bin/env python3
"""Structural tests of `stc plot` and `stc run --plot` (no golden SVGs).

usage: plot_test.py STC CASE [SOURCE_DIR]
The SVG marks what it draws: <g class="panel" data-kind=...>, <g class="series"
data-var=...>, <g class="lane" data-var=...> (BOOL), <g class="band" data-var=...>
(enums, strings), <text class="legend|xtick|ytick|lane-name">.
"""
import atexit
import math
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

STC = sys.argv[1]
CASE = sys.argv[2]
SRC = sys.argv[3] if len(sys.argv) > 3 else ""
NS = "{http://www.w3.org/2000/svg}"
TMP = tempfile.mkdtemp(prefix="stc-plot-test-")
if not os.environ.get("STC_PLOT_TEST_KEEP"):  # keep the files to look at them
    atexit.register(shutil.rmtree, TMP, True)


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def stc(*args):
    p = subprocess.run([STC, *args], capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def write_csv(name, header, rows):
    path = os.path.join(TMP, name)
    with open(path, "w") as f:
        f.write(",".join(["time"] + header) + "\n")
        for r in rows:
            f.write(",".join(r) + "\n")
    return path


def seconds(i, step_ms):
    ns = i * step_ms * 1_000_000
    s = str(ns // 1_000_000_000)
    frac = ns % 1_000_000_000
    if frac:
        s += "." + f"{frac:09d}".rstrip("0")
    return s


def real(v):
    s = repr(float(v))
    return s.replace("e", "E") if "e" in s else s


def parse(path):
    try:
        return ET.parse(path).getroot()
    except ET.ParseError as e:
        fail(f"{path} is not well-formed XML: {e}")


def groups(root, cls):
    return [g for g in root.iter(NS + "g") if g.get("class") == cls]


def texts(node, cls):
    return [t.text for t in node.iter(NS + "text") if t.get("class") == cls]


def expect(cond, msg):
    if not cond:
        fail(msg)


def motion_trace(step_ms=10, seconds_total=10):
    """Position ramp 0..100, velocity, a counter, two BOOLs, an enum state, a TIME."""
    header = ["Axis1.fActPosition", "Axis1.fActVelocity", "MAIN.count", "MAIN.bRun", "MAIN.move.Done",
              "MAIN.state", "MAIN.elapsed"]
    rows = []
    n = seconds_total * 1000 // step_ms
    for i in range(n + 1):
        t = i * step_ms / 1000
        state = "E_State#Idle" if t < 2 else "E_State#Moving" if t < 8 else "E_State#Done"
        rows.append([seconds(i, step_ms), real(10.0 * t), real(10.0 if 2 <= t < 8 else 0.0), str(i),
                     "TRUE" if 2 <= t < 8 else "FALSE", "TRUE" if t >= 8 else "FALSE", state,
                     f"T#{i * step_ms}ms" if i else "T#0s"])
    return write_csv("motion.csv", header, rows)


def case_structure():
    csv = motion_trace()
    svg = os.path.join(TMP, "motion.svg")
    rc, out = stc("plot", csv, "-o", svg, "--title", "Demo <1>")
    expect(rc == 0, f"stc plot exit {rc}: {out}")
    root = parse(svg)
    kinds = [g.get("data-kind") for g in groups(root, "panel")]
    expect(kinds == ["position", "velocity", "other", "time"], f"panels {kinds}")
    series = [g.get("data-var") for g in groups(root, "series")]
    expect(series == ["Axis1.fActPosition", "Axis1.fActVelocity", "MAIN.count", "MAIN.elapsed"], f"series {series}")
    lanes = [g.get("data-var") for g in groups(root, "lane")]
    expect(lanes == ["MAIN.bRun", "MAIN.move.Done"], f"lanes {lanes}")
    bands = [g.get("data-var") for g in groups(root, "band")]
    expect(bands == ["MAIN.state"], f"bands {bands}")
    expect(texts(root, "legend") == series, f"legend {texts(root, 'legend')}")
    expect(texts(root, "lane-name") == lanes + bands, f"lane names {texts(root, 'lane-name')}")
    expect(texts(root, "xtick") == ["0", "2", "4", "6", "8", "10"], f"x ticks {texts(root, 'xtick')}")
    expect(texts(root, "title") == ["Demo <1>"], "title (escaped)")
    pos = groups(root, "panel")[0]
    expect(texts(pos, "ytick") == ["0", "50", "100"], f"position y ticks {texts(pos, 'ytick')}")
    expect(any("[u]" in (t.text or "") for t in pos.iter(NS + "text")), "position unit")
    expect(any("[u/s]" in (t.text or "") for t in groups(root, "panel")[1].iter(NS + "text")), "velocity unit")
    expect(any("[s]" in (t.text or "") for t in groups(root, "panel")[3].iter(NS + "text")), "TIME unit")
    labels = [t.text for t in root.iter(NS + "text") if t.get("class") == "state-label"]
    expect(labels == ["Idle", "Moving", "Done"], f"state labels {labels}")
    colors = [l.get("stroke") for g in groups(root, "series") for l in g.iter(NS + "polyline")]
    expect(len(set(colors)) == len(series), f"series colours not distinct: {colors}")
    print("ok")


def case_vars_window():
    csv = motion_trace()
    svg = os.path.join(TMP, "vars.svg")
    rc, out = stc("plot", csv, "-o", svg, "--vars", "main.STATE,Axis1.fActPosition", "--vars", "MAIN.bRun",
                  "--from", "2s", "--to", "4")
    expect(rc == 0, f"exit {rc}: {out}")
    root = parse(svg)
    expect([g.get("data-var") for g in groups(root, "series")] == ["Axis1.fActPosition"], "series")
    expect([g.get("data-var") for g in groups(root, "lane")] == ["MAIN.bRun"], "lanes")
    expect([g.get("data-var") for g in groups(root, "band")] == ["MAIN.state"], "bands")
    xt = texts(root, "xtick")
    expect(xt[0] == "2.0" and xt[-1] == "4.0" and len(xt) >= 5, f"window ticks {xt}")
    expect(texts(root, "subtitle")[0].startswith("201 samples"), texts(root, "subtitle"))
    # Default output name: the trace's name with .svg; default title: the trace file's name.
    rc, out = stc("plot", csv)
    expect(rc == 0 and os.path.exists(csv[:-4] + ".svg"), f"default output: {rc} {out}")
    expect(texts(parse(csv[:-4] + ".svg"), "title") == ["motion.csv"], "default title")
    print("ok")


def case_downsample():
    # 100k rows, 1 ms: a noisy sine with one spike, a BOOL toggling every row with
    # one isolated pulse elsewhere, an enum changing every 3 rows, a hex WORD.
    n = 100_000
    rows = []
    for i in range(n):
        v = 50 * math.sin(i / 2000) + (1 if i % 2 else -1)
        if i == 77_777:
            v = 1000.0
        toggle = "TRUE" if (i < 10_000 and i % 2) else "FALSE"
        pulse = "TRUE" if i == 55_555 else "FALSE"
        rows.append([seconds(i, 1), real(v), toggle, pulse, f"E#S{(i // 3) % 5}", f"16#{i & 0xFFFF:X}"])
    csv = write_csv("big.csv", ["MAIN.fValue", "MAIN.bToggle", "MAIN.bPulse", "MAIN.eState", "MAIN.wWord"], rows)
    svg = os.path.join(TMP, "big.svg")
    rc, out = stc("plot", csv, "-o", svg)
    expect(rc == 0, f"exit {rc}: {out}")
    size = os.path.getsize(svg)
    expect(size < 1_000_000, f"SVG is {size} bytes")
    root = parse(svg)
    panel = groups(root, "panel")[0]
    yt = [float(t) for t in texts(panel, "ytick")]
    expect(max(yt) >= 1000, f"the spike was lost: y ticks {yt}")
    # The spike's point is drawn: some polyline point lies at the top of the data.
    ys = [float(p.split(",")[1]) for pl in panel.iter(NS + "polyline") for p in pl.get("points").split()]
    top = [r for r in panel.iter(NS + "rect")][0]
    expect(min(ys) < float(top.get("y")) + 0.1 * float(top.get("height")), "spike not drawn")
    lanes = {g.get("data-var"): g for g in groups(root, "lane")}
    pulse_paths = [p.get("d") for p in lanes["MAIN.bPulse"].iter(NS + "path") if p.get("class") != "wave"]
    expect(pulse_paths, "the one-sample pulse was lost")
    toggle_paths = [p.get("d") for p in lanes["MAIN.bToggle"].iter(NS + "path") if p.get("fill-opacity") == "0.6"]
    expect(toggle_paths, "the fast toggling is not shown as a band")
    expect(len(groups(root, "series")) == 2, "the WORD column is a number series")
    # 0 .. 99.999 s: the axis runs on to the round 100.
    expect(texts(root, "xtick") == ["0", "20", "40", "60", "80", "100"], f"x ticks {texts(root, 'xtick')}")
    print(f"ok ({size} bytes)")


def case_errors():
    rc, out = stc("plot", os.path.join(TMP, "nosuch.csv"), "-o", os.path.join(TMP, "x.svg"))
    expect(rc == 2 and "cannot open" in out and "nosuch.csv" in out, f"missing file: {rc} {out}")
    csv = motion_trace()
    rc, out = stc("plot", csv, "-o", os.path.join(TMP, "x.svg"), "--vars", "MAIN.nosuch")
    expect(rc == 2 and "no column 'MAIN.nosuch'" in out and "MAIN.bRun" in out, f"unknown var: {rc} {out}")
    rc, out = stc("plot", csv, "-o", os.path.join(TMP, "x.svg"), "--from", "soon")
    expect(rc == 2 and "not a time" in out, f"bad --from: {rc} {out}")
    rc, out = stc("plot", csv, "-o", os.path.join(TMP, "x.svg"), "--from", "5s", "--to", "1s")
    expect(rc == 2 and "--from" in out, f"--from after --to: {rc} {out}")
    bad = write_csv("bad.csv", ["A"], [["0", "1"], ["oops"]])
    rc, out = stc("plot", bad, "-o", os.path.join(TMP, "x.svg"))
    expect(rc == 1 and "bad.csv:3" in out, f"bad row: {rc} {out}")
    rc, out = stc("plot", csv, "-o", os.path.join(TMP, "nodir", "x.svg"))
    expect(rc == 1 and "cannot open" in out, f"unwritable output: {rc} {out}")
    print("ok")


def case_run():
    st = os.path.join(SRC, "tests/run/motion_move_absolute.st")
    svg, csv = os.path.join(TMP, "run.svg"), os.path.join(TMP, "run.csv")
    trace = "Axis1.fSetPosition,Axis1.fSetVelocity,MAIN.move.Busy,MAIN.move.Done,Axis1.nAxisState"
    rc, out = stc("run", st, "--lib", "codesys_sm3", "--for", "10.2s", "--trace", trace, "--plot", svg,
                  "--trace-out", csv, "--watch", "MAIN.doneCycle")
    expect(rc == 0 and "MAIN.doneCycle = 10103" in out, f"run: {rc} {out}")
    expect(open(csv).readline().strip() == "time," + trace, "the CSV is still written")
    root = parse(svg)
    expect([g.get("data-kind") for g in groups(root, "panel")] == ["position", "velocity"], "panels")
    expect([g.get("data-var") for g in groups(root, "lane")] == ["MAIN.move.Busy", "MAIN.move.Done"], "lanes")
    expect("discrete_motion" in [t.text for t in root.iter(NS + "text") if t.get("class") == "state-label"], "state label")
    expect(texts(root, "xtick") == ["0", "2", "4", "6", "8", "10"], f"x ticks {texts(root, 'xtick')}")
    expect(texts(root, "title") == ["motion_move_absolute"], "title")
    # Without --trace-out: a temporary CSV, removed afterwards.
    before = set(os.listdir(tempfile.gettempdir()))
    svg2 = os.path.join(TMP, "run2.svg")
    rc, out = stc("run", st, "--lib", "codesys_sm3", "--for", "1s", "--trace", "Axis1.fSetPosition", "--plot", svg2)
    expect(rc == 0 and len(groups(parse(svg2), "series")) == 1, f"run without --trace-out: {rc} {out}")
    left = [f for f in set(os.listdir(tempfile.gettempdir())) - before if f.startswith("stc-plot-") and f.endswith(".csv")]
    expect(not left, f"temporary trace left behind: {left}")
    rc, out = stc("run", st, "--lib", "codesys_sm3", "--for", "1s", "--plot", svg2)
    expect(rc == 2 and "--plot needs --trace" in out, f"--plot without --trace: {rc} {out}")
    rc, out = stc("run", st, "--lib", "codesys_sm3", "--for", "1s", "--trace", "Axis1.fSetPosition", "--plot", svg2,
                  "--trace-out", os.path.join(TMP, "t.vcd"))
    expect(rc == 2 and "CSV" in out, f"--plot with a VCD trace: {rc} {out}")
    print("ok")


def panel_ticks(root):
    """{panel title: [y tick labels]}."""
    out = {}
    for g in groups(root, "panel"):
        title = texts(g, "panel-title")[0]
        out[title] = texts(g, "ytick")
    return out


def case_ticks():
    """Nice ticks for any range, integer counters at integers, clean times."""
    header = ["Axis1.fActVelocity", "Axis1.fActPosition", "MAIN.count", "MAIN.k", "MAIN.tiny", "MAIN.huge"]
    rows = []
    for i in range(420):
        t = i / 100
        rows.append([seconds(i, 10), real(406 * math.sin(2 * math.pi * t / 4.2) if i != 105 else 406.0),
                     real(-12 - 938 * t / 4.19), str(i % 2), "3.7", real(1e-7 * t / 4.19), real(1e9 * t / 4.19)])
    rows.append(["4.199999999", real(0.0), "-950.0", "1", "3.7", "1.0E-07", "1.0E+09"])
    csv = write_csv("ticks.csv", header, rows)
    svg = os.path.join(TMP, "ticks.svg")
    rc, out = stc("plot", csv, "-o", svg)
    expect(rc == 0, f"exit {rc}: {out}")
    root = parse(svg)
    ticks = panel_ticks(root)
    for title, labels in ticks.items():
        expect(3 <= len(labels) <= 10, f"{title}: {len(labels)} ticks {labels}")
        expect(len(set(labels)) == len(labels), f"{title}: labels repeat {labels}")
    expect(ticks["velocity [u/s]"] == ["-400", "-200", "0", "200", "400"], f"symmetric: {ticks}")
    expect(all(l.startswith("-") or l == "0" for l in ticks["position [u]"]), f"negative-only: {ticks}")
    expect(ticks["MAIN.count"] == ["0", "1", "2"], f"integer counter: {ticks['MAIN.count']}")
    k = [float(x) for x in ticks["MAIN.k"]]
    expect(min(k) < 3.7 < max(k), f"constant 3.7: {k}")
    tiny = [float(x) for x in ticks["MAIN.tiny"]]
    expect(max(tiny) <= 1.2e-7 and max(tiny) >= 0.5e-7, f"tiny: {ticks['MAIN.tiny']}")
    huge = [float(x) for x in ticks["MAIN.huge"]]
    expect(max(huge) >= 0.5e9, f"huge: {ticks['MAIN.huge']}")
    sub = texts(root, "subtitle")[0]
    expect(sub.endswith("0 s to 4.2 s"), f"subtitle {sub}")
    # Any data, no crash: one row, NaN, Inf, constant.
    for name, rows in [("one.csv", [["0", "1.5", "7"]]),
                       ("nan.csv", [["0", "NaN", "1"], ["0.1", "NaN", "2"]]),
                       ("inf.csv", [["0", "Inf", "-1"], ["0.1", "-Inf", "1"], ["0.2", "1.0E+308", "2"]]),
                       ("flat.csv", [["0", "0.0", "0"], ["0.1", "0.0", "0"]])]:
        path = write_csv(name, ["MAIN.x", "MAIN.n"], rows)
        rc, out = stc("plot", path, "-o", os.path.join(TMP, name + ".svg"))
        expect(rc == 0, f"{name}: exit {rc}: {out}")
        for title, labels in panel_ticks(parse(os.path.join(TMP, name + ".svg"))).items():
            expect(len(set(labels)) == len(labels) and len(labels) >= 2, f"{name} {title}: {labels}")
    print("ok")


def case_legend():
    """State bands show their values with their colours; BOOL lanes what high and low mean."""
    csv = motion_trace()
    svg = os.path.join(TMP, "legend.svg")
    rc, out = stc("plot", csv, "-o", svg)
    expect(rc == 0, f"exit {rc}: {out}")
    root = parse(svg)
    legends = groups(root, "state-legend")
    expect([g.get("data-var") for g in legends] == ["MAIN.state"], "one state legend")
    expect(texts(legends[0], "state-legend-entry") == ["Idle", "Moving", "Done"], texts(legends[0], "state-legend-entry"))
    expect(texts(legends[0], "state-legend-type") == ["E_State:"], texts(legends[0], "state-legend-type"))
    swatch = {t: r.get("fill") for t, r in zip(texts(legends[0], "state-legend-entry"),
                                               [r for r in legends[0].iter(NS + "rect") if r.get("class") == "swatch"])}
    band = groups(root, "band")[0]
    for r in band.iter(NS + "rect"):
        if r.get("class") == "state":
            name = r.find(NS + "title").text.split("#")[1]
            expect(swatch[name] == r.get("fill"), f"{name}: band {r.get('fill')} legend {swatch[name]}")
    expect(texts(groups(root, "bool-legend")[0], "bool-legend-entry") == ["TRUE", "FALSE"], "BOOL legend")
    # Many values: at most three rows, the rest counted.
    rows = [[seconds(i, 10), f"'msg{i}'"] for i in range(300)]
    many = write_csv("many.csv", ["MAIN.text"], rows)
    rc, out = stc("plot", many, "-o", svg)
    expect(rc == 0, f"exit {rc}: {out}")
    g = groups(parse(svg), "state-legend")[0]
    more = texts(g, "state-legend-more")
    expect(len(more) == 1 and more[0].startswith("+") and more[0].endswith(" more"), f"more {more}")
    shown = len(texts(g, "state-legend-entry"))
    expect(shown + int(more[0][1:].split()[0]) == 300, f"{shown} shown, {more}")
    print("ok")


def case_units():
    """The axes' units from the trace's #units line label the panels."""
    path = os.path.join(TMP, "units.csv")
    with open(path, "w") as f:
        f.write("# a comment\n#units,mm,mm,,deg\n")
        f.write("time,Axis1.fActPosition,Axis1.fActVelocity,MAIN.count,Rot.fActPosition\n")
        for i in range(100):
            f.write(f"{seconds(i, 10)},{real(i * 0.5)},{real(50.0)},{i},{real(i * 3.6)}\n")
    svg = os.path.join(TMP, "units.svg")
    rc, out = stc("plot", path, "-o", svg)
    expect(rc == 0, f"exit {rc}: {out}")
    root = parse(svg)
    titles = [texts(g, "panel-title")[0] for g in groups(root, "panel")]
    expect(titles == ["position [mm]", "velocity [mm/s]", "MAIN.count", "position [deg]"], f"titles {titles}")
    # A #units line that does not match the header.
    with open(path, "w") as f:
        f.write("#units,mm\ntime,A,B\n0,1,2\n")
    rc, out = stc("plot", path, "-o", svg)
    expect(rc == 1 and "units.csv:1" in out and "#units" in out, f"bad #units: {rc} {out}")
    # End to end: project.toml [[axis]] unit -> stc run's trace -> stc plot.
    proj = os.path.join(TMP, "unitproj")
    os.makedirs(os.path.join(proj, "src"))
    shutil.copy(os.path.join(SRC, "tests/run/motion_move_absolute.st"), os.path.join(proj, "src", "main.st"))

    def project(unit):
        with open(os.path.join(proj, "project.toml"), "w") as f:
            f.write(f'[project]\nname = "unitproj"\nlibraries = ["codesys_sm3"]\n\n[[axis]]\nname = "Axis1"\nunit = {unit}\n')
    project('"mm"')
    csv = os.path.join(TMP, "unitrun.csv")
    rc, out = stc("run", proj, "--for", "100ms", "--trace", "Axis1.fSetPosition,MAIN.cycle,axis1.fSetVelocity",
                  "--trace-out", csv, "--plot", svg)
    expect(rc == 0, f"run: {rc} {out}")
    first = open(csv).readline().strip()
    expect(first == "#units,mm,,mm", f"units line {first}")
    titles = [texts(g, "panel-title")[0] for g in groups(parse(svg), "panel")]
    expect("position [mm]" in titles and "velocity [mm/s]" in titles, f"titles {titles}")
    for bad in ['""', '"m m"', '"a,b"', '"seventeen_chars_x"', "5"]:
        project(bad)
        rc, out = stc("run", proj, "--for", "10ms", "--trace", "Axis1.fSetPosition", "--trace-out", csv)
        expect(rc != 0 and "unit" in out and "project.toml:7" in out, f"unit = {bad}: {rc} {out}")
    print("ok")


def read_rows(path):
    """The data rows of a trace CSV (after the header) as lists of fields."""
    with open(path) as f:
        lines = [l.rstrip("\n") for l in f if l.strip() and not l.startswith("#")]
    return [l.split(",") for l in lines[1:]]


def compare_traces():
    """Expected and actual: the position differs from 3 s to 5 s, the state from 6 s on,
    MAIN.bRun is equal, MAIN.old is only expected, MAIN.extra only actual."""
    header = ["Axis1.fActPosition", "MAIN.bRun", "MAIN.state", "MAIN.old"]
    exp, act = [], []
    for i in range(1001):
        t = i / 100
        pos = 10.0 * t
        state = "E_State#Idle" if t < 6 else "E_State#Moving"
        exp.append([seconds(i, 10), real(pos), "TRUE" if t >= 2 else "FALSE", state, str(i)])
        apos = pos + (0.5 if 3 <= t < 5 else 1e-12)   # 1e-12: within the default tolerance
        astate = "E_State#Idle" if t < 6 else "E_State#Done"
        act.append([seconds(i, 10), real(apos), "TRUE" if t >= 2 else "FALSE", astate, "7"])
    e = write_csv("expected.csv", header, exp)
    a = write_csv("actual.csv", ["Axis1.fActPosition", "MAIN.bRun", "MAIN.state", "MAIN.extra"], act)
    return e, a


def x_of_time(root):
    xt = [(float(t.get("x")), float(t.text)) for t in root.iter(NS + "text") if t.get("class") == "xtick"]
    (p0, v0), (p1, v1) = xt[0], xt[-1]
    return lambda v: p0 + (v - v0) * (p1 - p0) / (v1 - v0)


def case_compare():
    e, a = compare_traces()
    svg = os.path.join(TMP, "compare.svg")
    rc, out = stc("plot", "--compare", e, a, "-o", svg)
    expect(rc == 0, f"exit {rc}: {out}")
    root = parse(svg)
    title = texts(root, "title")[0]
    expect(title == "expected.csv vs actual.csv: 4 of 5 variables differ", f"title {title}")
    only = texts(root, "only")
    expect(only == ["only in expected: MAIN.old; only in actual: MAIN.extra"], f"only {only}")
    blocks = {g.get("data-var"): g for g in groups(root, "compare")}
    expect(list(blocks) == ["Axis1.fActPosition", "MAIN.bRun", "MAIN.state", "MAIN.old", "MAIN.extra"], f"blocks {list(blocks)}")
    # Both series of the position, the expected one dashed.
    series = [(g.get("data-var"), g.get("data-trace")) for g in groups(blocks["Axis1.fActPosition"], "series")]
    expect(series == [("Axis1.fActPosition", "expected"), ("Axis1.fActPosition", "actual")], f"series {series}")
    dashed = [pl.get("stroke-dasharray") for g in groups(blocks["Axis1.fActPosition"], "series") for pl in g.iter(NS + "polyline")]
    expect(dashed[0] and not dashed[-1], f"dashes {dashed}")
    lanes = [g.get("data-trace") for g in groups(blocks["MAIN.bRun"], "lane")]
    expect(lanes == ["expected", "actual"], f"lanes {lanes}")
    bands = [g.get("data-trace") for g in groups(blocks["MAIN.state"], "band")]
    expect(bands == ["expected", "actual"], f"bands {bands}")
    expect(texts(groups(blocks["MAIN.state"], "state-legend")[0], "state-legend-entry") == ["Idle", "Moving", "Done"], "state legend")
    # Shading: where the values differ, nowhere else.
    x = x_of_time(root)
    shades = lambda var: [(float(r.get("x")), float(r.get("x")) + float(r.get("width")))
                          for r in blocks[var].iter(NS + "rect") if r.get("class") == "diff"]
    pos = shades("Axis1.fActPosition")
    expect(len(pos) == 1 and abs(pos[0][0] - x(3)) < 2 and abs(pos[0][1] - x(5)) < 2, f"position shading {pos} vs {x(3)}..{x(5)}")
    st = shades("MAIN.state")
    expect(len(st) == 1 and abs(st[0][0] - x(6)) < 2 and st[0][1] >= x(10) - 2, f"state shading {st}")
    expect(shades("MAIN.bRun") == [], "equal BOOL shaded")
    expect(blocks["MAIN.bRun"].get("data-differs") == "false", "MAIN.bRun differs?")
    # A tolerance that takes in the 0.5 offset (relative to |expected| up to 50): the position is equal.
    rc, out = stc("plot", "--compare", e, a, "-o", svg, "--tolerance", "0.02", "--vars", "Axis1.fActPosition,MAIN.bRun")
    root = parse(svg)
    expect(rc == 0 and texts(root, "title")[0].endswith(": no differences"), f"tolerance: {rc} {out} {texts(root, 'title')}")
    expect(not [r for r in root.iter(NS + "rect") if r.get("class") == "diff"], "shading within the tolerance")
    # A trace against itself: no differences; default output name.
    rc, out = stc("plot", "--compare", e, e)
    expect(rc == 0 and os.path.exists(e[:-4] + ".compare.svg"), f"default output: {rc} {out}")
    expect(texts(parse(e[:-4] + ".compare.svg"), "title")[0].endswith(": no differences"), "self compare")
    # One row each, NaN against NaN and against a number, different lengths: no crash.
    one_e = write_csv("one_e.csv", ["A", "B"], [["0", "NaN", "1"]])
    one_a = write_csv("one_a.csv", ["A", "B"], [["0", "NaN", "2"]])
    rc, out = stc("plot", "--compare", one_e, one_a, "-o", svg)
    expect(rc == 0 and texts(parse(svg), "title")[0].endswith(": 1 of 2 variables differs"), f"one row: {rc} {out}")
    short = write_csv("short.csv", ["A", "B"], [["0", "1.0", "1"], ["0.5", "NaN", "1"]])
    rc, out = stc("plot", "--compare", one_e, short, "-o", svg)
    expect(rc == 0, f"lengths: {rc} {out}")
    # A golden file sampled every 10th row against the full trace of the same run: compared only
    # at the sampled times (held samples are not the ramp between them), so no differences; a
    # changed sampled value is still found.
    sampled = write_csv("sampled.csv", ["Axis1.fActPosition"], [[r[0], r[1]] for r in
                                                                  [row for k, row in enumerate(read_rows(e)) if k % 10 == 0]])
    rc, out = stc("plot", "--compare", sampled, e, "-o", svg, "--vars", "Axis1.fActPosition")
    expect(rc == 0 and texts(parse(svg), "title")[0].endswith(": no differences"), f"sampled: {rc} {out} {texts(parse(svg), 'title')}")
    changed = [[r[0], r[1]] for r in [row for k, row in enumerate(read_rows(e)) if k % 10 == 0]]
    changed[50][1] = "123.0"
    rc, out = stc("plot", "--compare", write_csv("changed.csv", ["Axis1.fActPosition"], changed), e, "-o", svg,
                  "--vars", "Axis1.fActPosition")
    expect(rc == 0 and texts(parse(svg), "title")[0].endswith(": 1 of 1 variable differs"), f"sampled change: {rc} {out} {texts(parse(svg), 'title')}")
    print("ok")


def case_compare_errors():
    e, a = compare_traces()
    svg = os.path.join(TMP, "x.svg")
    for args, code, msg in [(["--compare", e], 2, "--compare"),
                            (["--compare", e, os.path.join(TMP, "nosuch.csv")], 2, "cannot open"),
                            (["--compare", e, a, "--tolerance", "-1"], 2, "--tolerance: '-1' is not a finite number >= 0"),
                            (["--compare", e, a, "--tolerance", "nan"], 2, "--tolerance"),
                            (["--compare", e, a, "--tolerance", "1e999"], 2, "--tolerance"),
                            (["--compare", e, a, "--tolerance", "abc"], 2, "--tolerance"),
                            ([e, "--tolerance", "1e-3"], 2, "requires --compare"),
                            ([e, "--compare", e, a], 2, "one too many"),
                            (["--compare", e, a, "--xy", "A,B"], 2, "excludes"),
                            (["--compare", e, a, "--vars", "MAIN.nosuch"], 2, "no column 'MAIN.nosuch'"),
                            (["--compare", e, a, "--from", "5s", "--to", "1s"], 2, "--from"),
                            (["--compare", e, write_csv("empty.csv", ["A"], [])], 1, "has no samples")]:
        rc, out = stc("plot", *args, "-o", svg)
        expect(rc == code and msg in out, f"{args}: {rc} {out}")
    print("ok")


# --xy: path plots.  A circle of radius 10 around (5, -3), once round in 2 s (1 ms
# rows): the commanded path, and an "actual" one lagging 0.1 rad with one NaN row.
CX, CY, R, LAG = 5.0, -3.0, 10.0, 0.1


def circle_trace():
    n = 2000
    rows = []
    for i in range(n + 1):
        a = 2 * math.pi * i / n
        ax = real(CX + R * math.cos(a - LAG)) if i != 700 else "NaN"
        rows.append([seconds(i, 1), real(CX + R * math.cos(a)), real(CY + R * math.sin(a)), ax,
                     real(CY + R * math.sin(a - LAG)), "E_State#Run"])
    return write_csv("circle.csv", ["X.fSetPosition", "Y.fSetPosition", "X.fActPosition", "Y.fActPosition",
                                    "MAIN.state"], rows)


def axis_map(root):
    """Data coordinates of SVG points, from the tick labels: (scale x, scale y, to_data)."""
    def fit(pairs):
        (p0, v0), (p1, v1) = pairs[0], pairs[-1]
        a = (p1 - p0) / (v1 - v0)
        return a, p0 - a * v0
    xt = [(float(t.get("x")), float(t.text)) for t in root.iter(NS + "text") if t.get("class") == "xtick"]
    yt = [(float(t.get("y")) - 4, float(t.text)) for t in root.iter(NS + "text") if t.get("class") == "ytick"]
    expect(len(xt) >= 3 and len(yt) >= 3, f"ticks {xt} {yt}")
    ax, bx = fit(xt)
    ay, by = fit(yt)
    for p, v in xt:
        expect(abs(ax * v + bx - p) < 0.1, f"x ticks not evenly spaced: {xt}")
    for p, v in yt:
        expect(abs(ay * v + by - p) < 0.1, f"y ticks not evenly spaced: {yt}")
    steps = {round(b[1] - a[1], 9) for a, b in zip(xt, xt[1:])} | {round(b[1] - a[1], 9) for a, b in zip(yt, yt[1:])}
    step = next(iter(steps))
    mantissa = step / 10 ** math.floor(math.log10(step))
    expect(len(steps) == 1 and any(abs(mantissa - m) < 1e-6 for m in (1, 2, 5)),
           f"tick steps not one round 1/2/5 value: {steps}")
    return ax, ay, lambda x, y: ((x - bx) / ax, (y - by) / ay)


def path_points(g):
    return [[tuple(map(float, pt.split(","))) for pt in pl.get("points").split()] for pl in g.iter(NS + "polyline")]


def marker(g, cls):
    for e in g.iter():
        if e.get("class") == cls:
            if e.tag == NS + "circle":
                return float(e.get("cx")), float(e.get("cy"))
            return float(e.get("x")) + 3.5, float(e.get("y")) + 3.5
    fail(f"no {cls} marker in {g.attrib}")


def near(p, q, tol=0.05):
    return abs(p[0] - q[0]) < tol and abs(p[1] - q[1]) < tol


def on_circle(pt, tol=0.05):
    return abs(math.hypot(pt[0] - CX, pt[1] - CY) - R) < tol


def case_xy_circle():
    csv = circle_trace()
    svg = os.path.join(TMP, "circle.svg")
    args = ["plot", csv, "-o", svg, "--xy", "X.fSetPosition,Y.fSetPosition", "--xy", "x.fActPosition,y.FACTPOSITION"]
    rc, out = stc(*args)
    expect(rc == 0, f"exit {rc}: {out}")
    root = parse(svg)
    expect([g.get("data-kind") for g in groups(root, "panel")] == ["path"], "one path panel")
    expect(not groups(root, "series") and not groups(root, "lane") and not groups(root, "band"), "no time plot")
    paths = groups(root, "path")
    expect([(g.get("data-x"), g.get("data-y")) for g in paths] ==
           [("X.fSetPosition", "Y.fSetPosition"), ("X.fActPosition", "Y.fActPosition")], f"paths {[g.attrib for g in paths]}")
    expect(texts(root, "legend") == ["X.fSetPosition, Y.fSetPosition", "X.fActPosition, Y.fActPosition"],
           f"legend {texts(root, 'legend')}")
    expect(texts(root, "legend-marker") == ["start", "end"], "marker legend")
    expect(texts(root, "xlabel") == ["X.fSetPosition, X.fActPosition [u]"], f"x label {texts(root, 'xlabel')}")
    expect(texts(root, "ylabel") == ["Y.fSetPosition, Y.fActPosition [u]"], f"y label {texts(root, 'ylabel')}")
    colors = [pl.get("stroke") for g in paths for pl in g.iter(NS + "polyline")]
    expect(len(set(colors)) == 2, f"path colours {colors}")
    # The panel is square and both axes have the same scale.
    box = [r for r in groups(root, "panel")[0].iter(NS + "rect")][0]
    expect(box.get("width") == box.get("height"), f"panel {box.attrib}")
    sx, sy, to_data = axis_map(root)
    expect(abs(sx + sy) < 1e-3 * abs(sx), f"scales differ: x {sx} px/u, y {sy} px/u")
    # Every drawn point, mapped back through the axes, lies on the circle.
    cmd, act = path_points(paths[0]), path_points(paths[1])
    expect(len(cmd) == 1 and len(cmd[0]) > 100, f"commanded path: {len(cmd)} lines")
    expect(len(act) == 2, f"the NaN row splits the actual path: {len(act)} lines")
    for line in cmd + act:
        for x, y in line:
            expect(on_circle(to_data(x, y)), f"point {x},{y} -> {to_data(x, y)} is off the circle")
    xs = [x for x, _ in cmd[0]]
    ys = [y for _, y in cmd[0]]
    w, h = max(xs) - min(xs), max(ys) - min(ys)
    expect(abs(w - h) <= 1 and w > 300, f"the circle's box is {w} x {h} px")
    # Start and end markers: both paths start at angle 0 (minus the lag) and end there.
    expect(near(to_data(*marker(paths[0], "start")), (CX + R, CY)), "commanded start")
    expect(near(to_data(*marker(paths[0], "end")), (CX + R, CY)), "commanded end")
    lagged = (CX + R * math.cos(-LAG), CY + R * math.sin(-LAG))
    expect(near(to_data(*marker(paths[1], "start")), lagged), "actual start")
    expect(near(to_data(*marker(paths[1], "end")), lagged), "actual end")
    # Deterministic: the same bytes again.
    first = open(svg, "rb").read()
    rc, out = stc(*args)
    expect(rc == 0 and open(svg, "rb").read() == first, "a second run differs")
    print("ok")


def case_xy_window():
    # 0.5 s .. 1 s is the second quarter: from (CX, CY + R) to (CX - R, CY).
    csv = circle_trace()
    svg = os.path.join(TMP, "quarter.svg")
    rc, out = stc("plot", csv, "-o", svg, "--xy", "X.fSetPosition,Y.fSetPosition", "--from", "500ms", "--to", "T#1s")
    expect(rc == 0, f"exit {rc}: {out}")
    root = parse(svg)
    expect(texts(root, "subtitle")[0].startswith("501 samples"), texts(root, "subtitle"))
    _, _, to_data = axis_map(root)
    g = groups(root, "path")[0]
    pts = [to_data(x, y) for line in path_points(g) for x, y in line]
    for p in pts:
        expect(on_circle(p) and p[0] <= CX + 0.05 and p[1] >= CY - 0.05, f"{p} is outside the quarter")
    expect(near(to_data(*marker(g, "start")), (CX, CY + R)), f"start {to_data(*marker(g, 'start'))}")
    expect(near(to_data(*marker(g, "end")), (CX - R, CY)), f"end {to_data(*marker(g, 'end'))}")
    # The axes cover the quarter, not the whole circle.
    xt = [float(t) for t in texts(root, "xtick")]
    expect(min(xt) >= CX - R - 2 and max(xt) <= CX + 2, f"x ticks {xt}")
    print("ok")


def case_xy_errors():
    csv = circle_trace()
    out_svg = os.path.join(TMP, "x.svg")
    rc, out = stc("plot", csv, "-o", out_svg, "--xy", "X.fSetPositon,Y.fSetPosition")
    expect(rc == 2 and "--xy: no column 'X.fSetPositon'" in out and "did you mean 'X.fSetPosition'?" in out,
           f"misspelt --xy name: {rc} {out}")
    rc, out = stc("plot", csv, "-o", out_svg, "--xy", "X.fSetPosition,MAIN.nothing")
    expect(rc == 2 and "no column 'MAIN.nothing'" in out and "MAIN.state" in out, f"unknown --xy name: {rc} {out}")
    rc, out = stc("plot", csv, "-o", out_svg, "--xy", "X.fSetPosition,MAIN.state")
    expect(rc == 2 and "'MAIN.state'" in out and "not a numeric column" in out, f"non-numeric --xy: {rc} {out}")
    for bad in ["X.fSetPosition", "X.fSetPosition,", "A,B,C"]:
        rc, out = stc("plot", csv, "-o", out_svg, "--xy", bad)
        expect(rc == 2 and "not a pair" in out, f"--xy {bad}: {rc} {out}")
    rc, out = stc("plot", csv, "-o", out_svg, "--xy", "X.fSetPosition,Y.fSetPosition", "--vars", "X.fSetPosition")
    expect(rc == 2 and "excludes" in out, f"--xy with --vars: {rc} {out}")
    rc, out = stc("plot", csv, "-o", out_svg, "--vars", "MAIN.stat")
    expect(rc == 2 and "did you mean 'MAIN.state'?" in out, f"--vars hint: {rc} {out}")
    print("ok")


# stc run --plot --xy: the path of a group's circle, drawn after the run.
def case_run_xy():
    st = os.path.join(SRC, "tests/run/group_path_line_circle.st")
    svg = os.path.join(TMP, "run_xy.svg")
    rc, out = stc("run", st, "--lib", "codesys_sm3", "--for", "12s", "--trace", "X.fSetPosition,Y.fSetPosition",
                  "--plot", svg, "--xy", "X.fSetPosition,Y.fSetPosition")
    expect(rc == 0, f"run --plot --xy: {rc} {out}")
    root = parse(svg)
    expect([g.get("data-kind") for g in groups(root, "panel")] == ["path"], "one path panel")
    paths = groups(root, "path")
    expect(len(paths) == 1 and paths[0].get("data-x") == "X.fSetPosition" and paths[0].get("data-y") == "Y.fSetPosition",
           "the pair drawn")
    rc, out = stc("run", st, "--lib", "codesys_sm3", "--for", "1s", "--trace", "X.fSetPosition", "--plot", svg,
                  "--xy", "X.fSetPosition")
    expect(rc == 2 and "not a pair" in out and "MAIN." not in out, f"malformed --xy refused before the run: {rc} {out}")
    rc, out = stc("run", st, "--lib", "codesys_sm3", "--for", "1s", "--xy", "A,B")
    expect(rc == 2 and "--xy requires --plot" in out, f"--xy without --plot: {rc} {out}")
    print("ok")


# --gcode: the commanded tool path of a G-code program (docs/cnc.md, "Seeing a program").
GDIR = os.path.join(SRC, "tests/cli/gcode_plot")
PART = os.path.join(GDIR, "part.cnc")
# part.cnc's moves: source line -> (class, data-move, programmed end point in X/Y).
PART_MOVES = {3: ("rapid", None, (10, 0)), 4: ("feed", "LIN", (50, 0)), 5: ("feed", "CCLW", (50, 30)),
              6: ("feed", "LIN", (30, 30)), 7: ("feed", "SPLINE", (20, 40)), 8: ("feed", "SPLINE", (10, 30)),
              9: ("feed", "LIN", (10, 0)), 10: ("rapid", None, (30, 15)), 11: ("feed", "LIN", (30, 15)),
              12: ("feed", "CLW", (30, 15)), 13: ("rapid", None, (30, 15)), 14: ("feed", "ELLCCLW", (10, 15)),
              15: ("rapid", None, (0, 0))}


def program_paths(root):
    progs = groups(root, "program")
    expect(len(progs) == 1, f"one program group, got {len(progs)}")
    out = []
    for p in progs[0].iter(NS + "path"):
        pts = [tuple(map(float, t.split(","))) for t in p.get("d").replace("M", " ").replace("L", " ").split()]
        out.append((p, pts))
    return progs[0], out


def check_curve(pts, to_data, span, dist, what):
    """Every point, and every chord's midpoint, within rounding (0.1 px) or 0.1 % of the span of the curve."""
    for a, b in zip(pts, pts[1:]):
        for q in (a, ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)):
            d = dist(to_data(*q))
            expect(d < 0.001 * span, f"{what}: {q} -> {to_data(*q)} is {d} off the curve (span {span})")
    for q in pts:
        expect(dist(to_data(*q)) < 0.0002 * span, f"{what}: sample {to_data(*q)} off the curve")


def case_gcode_path():
    svg = os.path.join(TMP, "part.svg")
    rc, out = stc("plot", "--gcode", PART, "-o", svg)
    expect(rc == 0 and out == "", f"exit {rc}: {out}")
    root = parse(svg)
    expect([g.get("data-kind") for g in groups(root, "panel")] == ["path"], "one path panel")
    expect(texts(root, "title") == ["part.cnc"], f"title {texts(root, 'title')}")
    expect(texts(root, "subtitle") == ["program: 13 moves (9 feed, 4 rapid), X/Y plane"], f"subtitle {texts(root, 'subtitle')}")
    expect(texts(root, "legend") == ["commanded (feed)", "rapid (G0)"], f"legend {texts(root, 'legend')}")
    expect(texts(root, "xlabel") == ["X"] and texts(root, "ylabel") == ["Y"], "axis labels")
    expect(not groups(root, "path"), "no trace paths")
    prog, paths = program_paths(root)
    expect(prog.get("data-axes") == "X,Y" and prog.get("data-file") == PART, f"program {prog.attrib}")
    sx, sy, to_data = axis_map(root)
    expect(abs(sx + sy) < 1e-3 * abs(sx), f"scales differ: {sx} {sy}")
    span = 560 / abs(sx)
    lines = [int(p.get("data-line")) for p, _ in paths]
    expect(lines == sorted(PART_MOVES), f"one path per move, in order: {lines}")
    px = 0.08 / abs(sx)   # 0.1 px rounding of the SVG coordinates
    for p, pts in paths:
        cls, move, end = PART_MOVES[int(p.get("data-line"))]
        expect(p.get("class") == cls and p.get("data-move") == move, f"line {p.get('data-line')}: {p.attrib}")
        # Rapids dashed in their own colour, feeds solid.
        expect((p.get("stroke-dasharray") is not None) == (cls == "rapid"), f"dash of {p.attrib}")
        e = to_data(*pts[-1])
        expect(abs(e[0] - end[0]) < px and abs(e[1] - end[1]) < px, f"line {p.get('data-line')} ends at {e}, not {end}")
    expect(len({p.get("stroke") for p, _ in paths if p.get("class") == "rapid"} |
               {p.get("stroke") for p, _ in paths if p.get("class") == "feed"}) == 2, "two colours")
    by_line = {int(p.get("data-line")): pts for p, pts in paths}
    # The half circle around (50, 15), radius 15, through (65, 15).
    half = by_line[5]
    check_curve(half, to_data, span, lambda q: abs(math.hypot(q[0] - 50, q[1] - 15) - 15), "G3 half circle")
    expect(max(to_data(*q)[0] for q in half) > 65 - px, "the half circle bulges to x = 65")
    expect(len(half) > 10, f"the half circle has {len(half)} points")
    # The full circle around (35, 15), radius 5: no angular gap above 45 degrees.
    full = by_line[12]
    check_curve(full, to_data, span, lambda q: abs(math.hypot(q[0] - 35, q[1] - 15) - 5), "G2 full circle")
    ang = sorted(math.atan2(to_data(*q)[1] - 15, to_data(*q)[0] - 35) for q in full)
    gaps = [b - a for a, b in zip(ang, ang[1:])] + [ang[0] + 2 * math.pi - ang[-1]]
    expect(max(gaps) < math.pi / 4, f"the full circle has a gap of {max(gaps)} rad")
    # The half ellipse around (20, 15), a = 10 along X, b = 5: the upper half.
    ell = by_line[14]
    for q in ell:
        x, y = to_data(*q)
        expect(abs(((x - 20) / 10) ** 2 + ((y - 15) / 5) ** 2 - 1) < 0.01 and y > 15 - px, f"ellipse point {x},{y}")
    expect(max(to_data(*q)[1] for q in ell) > 20 - 2 * px, "the ellipse reaches y = 20")
    # The plunge (G1 Z-1) seen from above is a dot: a path of one point twice.
    expect(len(set(by_line[11])) == 1, f"the plunge {by_line[11]}")
    # Deterministic; the default output name is the program's.
    first = open(svg, "rb").read()
    rc, out = stc("plot", "--gcode", PART, "-o", svg)
    expect(rc == 0 and open(svg, "rb").read() == first, "a second run differs")
    copy = os.path.join(TMP, "copy.cnc")
    shutil.copy(PART, copy)
    rc, out = stc("plot", "--gcode", copy)
    expect(rc == 0 and os.path.exists(os.path.join(TMP, "copy.svg")), f"default output: {rc} {out}")
    print("ok")


def part_trace():
    """An 'actual' path: the big half circle with a radial error of 0.5 and a
    rapid flag on the first and last quarter of the time."""
    n = 400
    rows = []
    for i in range(n + 1):
        a = -math.pi / 2 + math.pi * i / n
        rows.append([seconds(i, 1), real(50 + 15.5 * math.cos(a)), real(15 + 15.5 * math.sin(a)), real(0.0),
                     "TRUE" if i < n // 4 or i > 3 * n // 4 else "FALSE", "E_S#Run"])
    return write_csv("actual.csv", ["X.pos", "Y.pos", "Z.pos", "G0", "MAIN.state"], rows)


def case_gcode_trace():
    csv = part_trace()
    svg = os.path.join(TMP, "both.svg")
    rc, out = stc("plot", csv, "--gcode", PART, "--xy", "X.pos,Y.pos", "--rapid", "g0", "-o", svg)
    expect(rc == 0, f"exit {rc}: {out}")
    root = parse(svg)
    expect(texts(root, "legend") == ["commanded (feed)", "rapid (G0)", "actual: X.pos, Y.pos", "actual, G0 (G0)"],
           f"legend {texts(root, 'legend')}")
    sub = texts(root, "subtitle")[0]
    expect(sub.startswith("401 samples") and "program: 13 moves" in sub, sub)
    # The program is drawn first, under the trace.
    order = [g.get("class") for g in root.iter(NS + "g") if g.get("class") in ("program", "path")]
    expect(order == ["program", "path"], f"drawing order {order}")
    _, _, to_data = axis_map(root)
    trace = groups(root, "path")[0]
    lines = list(trace.iter(NS + "polyline"))
    expect([pl.get("class") == "rapid" for pl in lines] == [True, False, True], f"runs {[pl.attrib for pl in lines]}")
    expect(all(pl.get("stroke-dasharray") for pl in lines if pl.get("class") == "rapid"), "rapid runs dashed")
    # The runs join: each ends where the next starts.
    pts = path_points(trace)
    for a, b in zip(pts, pts[1:]):
        expect(a[-1] == b[0], f"gap between runs: {a[-1]} {b[0]}")
    for line in pts:
        for q in line:
            x, y = to_data(*q)
            expect(abs(math.hypot(x - 50, y - 15) - 15.5) < 0.1, f"trace point {x},{y}")
    # X/Z plane: the plunge at x = 30 from z = 5 to z = -1 is a vertical line.
    svg2 = os.path.join(TMP, "xz.svg")
    rc, out = stc("plot", "--gcode", PART, "--gcode-axes", "x,z", "-o", svg2)
    expect(rc == 0, f"--gcode-axes: {rc} {out}")
    root = parse(svg2)
    prog, paths = program_paths(root)
    expect(prog.get("data-axes") == "X,Z" and texts(root, "xlabel") == ["X"] and texts(root, "ylabel") == ["Z"], "X,Z plane")
    _, _, to_data = axis_map(root)
    plunge = [to_data(*q) for p, pts in paths if p.get("data-line") == "11" for q in pts]
    expect(len(plunge) == 2 and all(abs(x - 30) < 0.05 for x, _ in plunge) and
           abs(plunge[0][1] - 5) < 0.05 and abs(plunge[1][1] + 1) < 0.05, f"plunge {plunge}")
    print("ok")


def case_gcode_errors():
    svg = os.path.join(TMP, "err.svg")
    broken = os.path.join(GDIR, "broken.cnc")
    rc, out = stc("plot", "--gcode", broken, "-o", svg)
    expect(rc == 1 and "broken.cnc:3:14: error: the radius 1 is smaller than half the chord" in out and
           "broken.cnc:4:8: error:" in out and "$depth$" in out and "--gcode-var" in out, f"decode errors: {rc} {out}")
    expect(not os.path.exists(svg), "no SVG for a broken program")
    rc, out = stc("plot", "--gcode", os.path.join(GDIR, "empty.cnc"), "-o", svg)
    expect(rc == 0, f"empty program: {rc} {out}")
    root = parse(svg)
    expect(texts(root, "note") == ["no moves in " + os.path.join(GDIR, "empty.cnc")] or
           texts(root, "note")[0].startswith("no moves in"), f"note {texts(root, 'note')}")
    expect("0 moves" in texts(root, "subtitle")[0], texts(root, "subtitle"))
    # $name$ values from --gcode-var.
    vars_ = os.path.join(GDIR, "vars.cnc")
    rc, out = stc("plot", "--gcode", vars_, "-o", svg)
    expect(rc == 1 and "unknown variable '$len$'" in out and "--gcode-var" in out, f"no values: {rc} {out}")
    rc, out = stc("plot", "--gcode", vars_, "-o", svg, "--gcode-var", "LEN=20", "--gcode-var", "h=10", "--gcode-var", "$Radius$=6")
    expect(rc == 0, f"--gcode-var: {rc} {out}")
    rc, out = stc("plot", "--gcode", vars_, "-o", svg, "--gcode-var", "len=20", "--gcode-var", "h=10", "--gcode-var", "radus=6")
    expect(rc == 1 and "did you mean '$radus$'" in out, f"--gcode-var hint: {rc} {out}")
    good = os.path.join(SRC, "tests/cli/gcode_project/nc/good.cnc")
    rc, out = stc("plot", "--gcode", good, "-o", svg, "--gcode-var", "xPos=20", "--gcode-var", "GVL.xPos=20",
                  "--gcode-var", "radius=10")
    # G0 X0 Y0 from the start position 0 is no move: the line, the arc, the line.
    expect(rc == 0 and len(program_paths(parse(svg))[1]) == 3, f"good.cnc: {rc} {out}")
    for bad in ["x", "x=", "=1", "x=1e999", "x=abc"]:
        rc, out = stc("plot", "--gcode", vars_, "-o", svg, "--gcode-var", bad)
        expect(rc == 2 and "NAME=VALUE" in out, f"--gcode-var {bad}: {rc} {out}")
    # Usage errors: exit 2.
    csv = part_trace()
    for args, msg in [([], "give a trace CSV, --gcode FILE, or both"),
                      (["--gcode", PART, "--xy", "X.pos,Y.pos"], "--xy needs a trace CSV"),
                      (["--gcode", PART, "--from", "1s"], "--from needs a trace CSV"),
                      ([csv, "--gcode", PART], "needs --xy"),
                      (["--gcode", PART, "--gcode-axes", "X,X"], "not two different axes"),
                      (["--gcode", PART, "--gcode-axes", "XY"], "not two different axes"),
                      ([csv, "--gcode-axes", "X,Z", "--xy", "X.pos,Y.pos"], "requires --gcode"),
                      ([csv, "--xy", "X.pos,Y.pos", "--rapid", "G1"], "--rapid: no column 'G1'"),
                      ([csv, "--xy", "X.pos,Y.pos", "--rapid", "MAIN.state"], "not a BOOL or numeric column"),
                      ([csv, "--rapid", "G0"], "requires --xy"),
                      (["--gcode", os.path.join(GDIR, "nothere.cnc")], "cannot open"),
                      ([csv, "--gcode", PART, "--vars", "X.pos"], "excludes")]:
        rc, out = stc("plot", *args, "-o", svg)
        expect(rc == 2 and msg in out, f"{args}: {rc} {out}")
    print("ok")


{"structure": case_structure, "vars-window": case_vars_window, "downsample": case_downsample,
 "errors": case_errors, "run": case_run, "xy-circle": case_xy_circle, "xy-window": case_xy_window,
 "xy-errors": case_xy_errors, "run-xy": case_run_xy, "gcode-path": case_gcode_path,
 "gcode-trace": case_gcode_trace, "gcode-errors": case_gcode_errors, "ticks": case_ticks, "legend": case_legend,
 "units": case_units, "compare": case_compare, "compare-errors": case_compare_errors}[CASE]()
