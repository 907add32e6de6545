#!/usr/bin/env python3
"""Reference traces from LinuxCNC's G-code interpreter rs274 for the CNC cross-check
(issue 16, item 3). A development tool: the build and the tests never run it, they read
the committed files under tests/cnc/rs274/ (format: tests/cnc/rs274/README.md).

    python3 tools/rs274_fixtures.py              # regenerate tests/cnc/rs274/
    python3 tools/rs274_fixtures.py --out DIR    # write the corpus into DIR instead
    python3 tools/rs274_fixtures.py --check      # regenerate into a temporary directory and
                                                 # compare with tests/cnc/rs274/ (or --out DIR);
                                                 # exit 1 on any difference
    python3 tools/rs274_fixtures.py --list       # the program names, one per line

What it does, for every program of the corpus (hand-written ones named h_*, random ones r_*,
random ones drawn from random.Random(<program name>), so the output is deterministic):
  1. writes the program twice from one description: ngc/<name>.ngc in rs274's spelling and
     din/<name>.cnc in our DIN 66025 spelling (Moons / CODESYS SoftMotion), line for line;
  2. runs LinuxCNC's interpreter on the .ngc three times:
       - through its Python binding (module `gcode`, the same librs274 as /usr/bin/rs274),
         which hands over every canonical call with the source line of the block that
         produced it, but a G21 program's lengths divided by 25.4;
       - the same with G20 in place of G21: the interpreter computes in program units, so this
         gives its doubles undivided; they are accepted only if v / 25.4 equals the G21 run's
         value bit for bit, for every value;
       - through the standalone binary `rs274 -g` (prints 4 decimals), as a cross-check:
         every motion must agree with the module's to 5e-5 mm;
     and checks every element outside tool compensation against what its block programs;
  3. writes trace/<name>.txt (one line per element, 17 significant digits) and index.txt.
A random program that rs274 refuses (cutter compensation gouges, for instance) is redrawn
from the same generator; the number of draws is deterministic too.

Needs the Debian package linuxcnc-uspace (apt-get install -y linuxcnc-uspace), which
provides /usr/bin/rs274 and the module gcode for /usr/bin/python3. The module is run in a
child /usr/bin/python3 process per program (it keeps global interpreter state and can crash
on input it does not support), so this script itself may run under any Python 3.
"""
import argparse
import filecmp
import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile
from decimal import Decimal

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_OUT = os.path.join(ROOT, "tests", "cnc", "rs274")
RS274 = "/usr/bin/rs274"
SYS_PYTHON = "/usr/bin/python3"
DIST_PACKAGES = "/usr/lib/python3/dist-packages"
PACKAGE = "linuxcnc-uspace"
HEADER_LINES = 4          # lines 1..4 of every program are the preamble (see Prog.texts)
BIN_TOLERANCE = 5.1e-5    # the binary prints %.4f

# ---------------------------------------------------------------------------------------------
# The tool table for the programs that use rs274's table form G41 D<tool> (tool.tbl, mm)
TOOLS = {1: 1000, 2: 2500, 3: 4000}      # tool number -> radius in micrometres

# ---------------------------------------------------------------------------------------------
# numbers: every coordinate of a program is an integer number of micrometres


def mm(v):
    """mm value (int, float or str) -> integer micrometres (must be exact)."""
    d = Decimal(str(v)) * 1000
    if d != d.to_integral_value():
        raise ValueError("%r mm is not a whole number of micrometres" % (v,))
    return int(d)


def fmt(u):
    """integer micrometres -> shortest decimal mm string (no exponent, no trailing zeros)."""
    sign = "-" if u < 0 else ""
    i, f = divmod(abs(u), 1000)
    return sign + str(i) + (("." + ("%03d" % f).rstrip("0")) if f else "")


def fmt_dec(d):
    d = Decimal(d).normalize()
    s = format(d, "f")
    return s


def num(v):
    """a double of the trace -> shortest round-trip decimal (Python repr), -0.0 as 0.0."""
    v = float(v)
    if v == 0.0:
        v = 0.0
    return repr(v)


# planes: G-code number -> (name as rs274's canon calls it, (first axis, second axis), normal axis)
# rs274 (and ISO 6983 / DIN 66025) order the plane's axes so that first x second = +normal:
# XY: X,Y (normal +Z); XZ: Z,X (normal +Y); YZ: Y,Z (normal +X).
PLANES = {17: ("XY", (0, 1), 2), 18: ("XZ", (2, 0), 1), 19: ("YZ", (1, 2), 0)}
CANON_PLANE = {1: 17, 2: 19, 3: 18}      # rs274's CANON_PLANE enum -> G code
AXES = "XYZ"
CENTRE_WORDS = "IJK"


class Prog:
    """One program of the corpus, built from one description into both spellings.

    Positions are absolute integer micrometres; the builder turns them into words for the
    active distance mode. Every motion block carries all of X, Y and Z (in G91 as explicit
    increments, zero included) and an arc every centre word of its plane, so that neither
    dialect's rules for omitted words matter (our dialect keeps omitted word values modally).
    """

    def __init__(self, name, kind, desc):
        assert "(" not in desc and ")" not in desc, "rs274 comments do not nest"
        self.name, self.kind, self.desc = name, kind, desc
        self.blocks = []          # (ngc text, din text, is_comment)
        self.pos = [0, 0, 0]
        self.inc = False
        self.plane = 17
        self.comp = None
        self.feed = None
        self.flags = set()
        self.comp_radius = {}     # source line -> (side, radius um)
        self.setpos = {}          # source line -> (x, y, z) um
        self.expect = {}          # source line -> what the block programs (checked against rs274)
        self.exit_pending = False
        self.tool_table = False

    # ---- bookkeeping
    def next_line(self):
        return HEADER_LINES + len(self.blocks) + 1

    def _add(self, ngc, din=None, comment=False):
        self.blocks.append((ngc, ngc if din is None else din, comment))

    def _feed_words(self, f):
        if f is None:
            return "", ""
        f = Decimal(str(f))
        if f <= 0:
            raise ValueError("feed must be positive")
        self.flags.add("feed")
        self.feed = f
        return " F" + fmt_dec(f * 60), " F" + fmt_dec(f)

    def _xyz(self, tgt):
        vals = [t - p for t, p in zip(tgt, self.pos)] if self.inc else tgt
        return " ".join("%s%s" % (a, fmt(v)) for a, v in zip(AXES, vals))

    # ---- modes
    def comment(self, text):
        assert "(" not in text and ")" not in text
        self._add("(%s)" % text, comment=True)

    def set_plane(self, g):
        assert g in PLANES and self.comp is None
        self.plane = g
        self._add("G%d" % g)

    def absolute(self):
        self.inc = False
        self._add("G90")

    def incremental(self):
        self.inc = True
        self.flags.add("g91")
        self._add("G91")

    def dwell(self, seconds):
        t = fmt_dec(Decimal(str(seconds)))
        self.flags.add("dwell")
        self._add("G4 P" + t, "G4 T" + t)

    def set_position(self, tgt):
        """G92: only in G90 and without tool compensation, with all three axes (where the
        dialects agree: the current position becomes tgt, no motion)."""
        tgt = list(tgt)
        assert not self.inc and self.comp is None
        self.setpos[self.next_line()] = tuple(tgt)
        self.flags.add("g92")
        self._add("G92 " + self._xyz(tgt))
        self.pos = tgt

    def comp_on(self, side, radius, tool=None):
        assert side in "LR" and self.comp is None and self.plane == 17 and radius > 0
        self.comp_radius[self.next_line()] = (side, radius)
        self.comp = side
        self.flags.add("comp_left" if side == "L" else "comp_right")
        g = "G41" if side == "L" else "G42"
        if tool is None:
            ngc = "%s.1 D%s" % (g, fmt(2 * radius))
        else:
            assert TOOLS[tool] == radius
            ngc = "%s D%d" % (g, tool)
            self.tool_table = True
            self.flags.add("tooltable")
        self._add(ngc, "%s D%s" % (g, fmt(radius)))

    def comp_off(self):
        assert self.comp is not None
        self.comp = None
        self.exit_pending = True
        self._add("G40")

    # ---- motion
    def move(self, g, tgt, f=None):
        tgt = list(tgt)
        assert g in ("G0", "G1")
        if tgt == self.pos:
            raise ValueError("zero-length move")
        if g == "G1" and f is None and self.feed is None:
            raise ValueError("first feed move without F")
        self.flags.add(g.lower())
        self._expect(g, tgt)
        fn, fd = self._feed_words(f)
        w = self._xyz(tgt)
        self._add("%s %s%s" % (g, w, fn), "%s %s%s" % (g, w, fd))
        self.pos = tgt

    def _expect(self, g, tgt, centre=None, r=None):
        self.expect[self.next_line()] = {
            "g": g, "start": list(self.pos), "end": list(tgt), "centre": centre, "r": r,
            "plane": self.plane, "compensated": self.comp is not None, "exit": self.exit_pending}
        self.exit_pending = False

    def arc(self, g, tgt, centre=None, r=None, f=None):
        """G2/G3 to tgt (absolute um), either about centre (absolute um; only its two plane
        coordinates count) or with radius r (um, negative: the arc longer than 180 degrees)."""
        tgt = list(tgt)
        assert g in ("G2", "G3") and (centre is None) != (r is None)
        if f is None and self.feed is None:
            raise ValueError("first feed move without F")
        name, (a1, a2), n = PLANES[self.plane]
        self.flags.add(name.lower())
        if tgt[n] != self.pos[n]:
            self.flags.add("helix")
        if centre is not None:
            rs = (self.pos[a1] - centre[a1]) ** 2 + (self.pos[a2] - centre[a2]) ** 2
            re_ = (tgt[a1] - centre[a1]) ** 2 + (tgt[a2] - centre[a2]) ** 2
            if rs != re_ or rs == 0:
                raise ValueError("inconsistent arc centre")
            full = tgt[a1] == self.pos[a1] and tgt[a2] == self.pos[a2]
            self.flags.add("full_circle" if full else "arc_centre")
            rel = [0, 0, 0]
            rel[a1] = centre[a1] - self.pos[a1]
            rel[a2] = centre[a2] - self.pos[a2]
            letters = sorted((CENTRE_WORDS[a1], CENTRE_WORDS[a2]))
            ngc_c = " ".join("%s%s" % (c, fmt(rel[CENTRE_WORDS.index(c)])) for c in letters)
            din_c = " ".join("%s%s" % (c, fmt(rel[i])) for i, c in enumerate(CENTRE_WORDS))
        else:
            chord2 = (tgt[a1] - self.pos[a1]) ** 2 + (tgt[a2] - self.pos[a2]) ** 2
            if chord2 == 0 or 4 * r * r <= chord2:
                raise ValueError("radius too small or zero chord")
            self.flags.add("arc_radius_negative" if r < 0 else "arc_radius")
            ngc_c = din_c = "R" + fmt(r)
        self._expect(g, tgt, centre, r)
        fn, fd = self._feed_words(f)
        w = self._xyz(tgt)
        self._add("%s %s %s%s" % (g, w, ngc_c, fn), "%s %s %s%s" % (g, w, din_c, fd))
        self.pos = tgt

    # ---- mm conveniences for the hand-written programs
    def _target(self, x, y, z):
        return [self.pos[0] if x is None else mm(x),
                self.pos[1] if y is None else mm(y),
                self.pos[2] if z is None else mm(z)]

    def g0(self, x=None, y=None, z=None):
        self.move("G0", self._target(x, y, z))

    def g1(self, x=None, y=None, z=None, f=None):
        self.move("G1", self._target(x, y, z), f)

    def _arc_mm(self, g, x, y, z, i, j, k, r, f):
        tgt = self._target(x, y, z)
        if r is not None:
            self.arc(g, tgt, r=mm(r), f=f)
        else:
            off = [mm(i or 0), mm(j or 0), mm(k or 0)]
            self.arc(g, tgt, centre=[p + o for p, o in zip(self.pos, off)], f=f)

    def g2(self, x=None, y=None, z=None, i=None, j=None, k=None, r=None, f=None):
        self._arc_mm("G2", x, y, z, i, j, k, r, f)

    def g3(self, x=None, y=None, z=None, i=None, j=None, k=None, r=None, f=None):
        self._arc_mm("G3", x, y, z, i, j, k, r, f)

    # ---- the two texts, line for line
    def texts(self):
        assert self.comp is None, "program ends with compensation on"
        ngc = ["(%s: %s)" % (self.name, self.desc),
               "G21 G91.1 (millimetres; I J K relative to the start point)",
               "G17", "G90"]
        din = ["(%s: %s)" % (self.name, self.desc),
               "(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)",
               "N30 G17", "N40 G90"]
        for n, (a, b, is_comment) in enumerate(self.blocks, HEADER_LINES + 1):
            ngc.append(a)
            din.append(b if is_comment else "N%d %s" % (10 * n, b))
        ngc.append("M2")
        din.append("(end of program: rs274 has M2 here, an M-function handshake in our dialect)")
        return "\n".join(ngc) + "\n", "\n".join(din) + "\n"


# ---------------------------------------------------------------------------------------------
# hand-written programs


def hand_written():
    progs = []

    def new(name, desc):
        p = Prog(name, "hand", desc)
        progs.append(p)
        return p

    p = new("h_lines_abs", "G0 and G1 lines in absolute coordinates")
    p.g0(10, 5, 2)
    p.g1(30, 5, 2, f=10)
    p.g1(30, 25.5, 2)
    p.g1(-12.25, 25.5, -3)
    p.g1(0, 0, 0)
    p.g0(0, 0, 10)
    p.g0(100, -50, 10)

    p = new("h_lines_inc", "G0 and G1 lines in incremental coordinates G91")
    p.incremental()
    p.g0(5, 5, 1)
    p.g1(15, 5, 1, f=20)
    p.g1(15, 15, 1)
    p.g1(5, 15, -1.5)
    p.g1(5, 5, -1.5)
    p.g0(5, 5, 10)
    p.g1(0.001, 0.002, 9.999)

    p = new("h_g90_g91_switch", "G90 and G91 switched between lines and arcs")
    p.g0(10, 10, 0)
    p.incremental()
    p.g1(20, 10, 0, f=5)
    p.g2(30, 20, 0, i=0, j=10)
    p.absolute()
    p.g1(30, 40, 0)
    p.incremental()
    p.g3(20, 50, 0, i=-10, j=0)
    p.g1(20, 50, -2)
    p.absolute()
    p.g1(0, 0, -2)

    p = new("h_arc_xy_cw_centre", "G17 G2 arcs by centre: quarter, half, three quarters")
    p.g0(10, 0, 0)
    p.g2(0, -10, i=-10, j=0, f=10)
    p.g2(0, 10, i=0, j=10)
    p.g2(-10, 20, i=0, j=10)
    p.g1(-10, 30)
    p.g2(0, 40, i=10, j=0)

    p = new("h_arc_xy_ccw_centre", "G17 G3 arcs by centre: quarter, half, three quarters")
    p.g0(10, 0, 0)
    p.g3(0, 10, i=-10, j=0, f=10)
    p.g3(0, -10, i=0, j=-10)
    p.g3(-10, -20, i=0, j=-10)
    p.g1(-10, -30)
    p.g3(-20, -40, i=0, j=-10)

    p = new("h_arc_xz_cw_centre",
            "G18 G2 arcs by I K; G2 is clockwise seen from +Y: from X10 Z0 a quarter ends at X0 Z10")
    p.set_plane(18)
    p.g0(10, 0, 0)
    p.g2(0, 0, 10, i=-10, k=0, f=10)
    p.g2(-10, 0, 0, i=0, k=-10)
    p.g2(10, 0, 0, i=10, k=0)
    p.g1(10, 0, -5)
    p.g2(5, 0, -10, i=-5, k=0)

    p = new("h_arc_xz_ccw_centre",
            "G18 G3 arcs by I K; G3 is counterclockwise seen from +Y: from X10 Z0 a quarter ends at X0 Z-10")
    p.set_plane(18)
    p.g0(10, 0, 0)
    p.g3(0, 0, -10, i=-10, k=0, f=10)
    p.g3(-10, 0, 0, i=0, k=10)
    p.g3(10, 0, 0, i=10, k=0)
    p.g1(10, 0, 5)
    p.g3(5, 0, 10, i=-5, k=0)

    p = new("h_arc_yz_cw_centre",
            "G19 G2 arcs by J K; clockwise seen from +X: from Y10 Z0 a quarter ends at Y0 Z-10")
    p.set_plane(19)
    p.g0(0, 10, 0)
    p.g2(0, 0, -10, j=-10, k=0, f=10)
    p.g2(0, -10, 0, j=0, k=10)
    p.g2(0, 10, 0, j=10, k=0)
    p.g1(3, 10, 0)
    p.g2(3, 5, 5, j=-5, k=0)

    p = new("h_arc_yz_ccw_centre",
            "G19 G3 arcs by J K; counterclockwise seen from +X: from Y10 Z0 a quarter ends at Y0 Z10")
    p.set_plane(19)
    p.g0(0, 10, 0)
    p.g3(0, 0, 10, j=-10, k=0, f=10)
    p.g3(0, -10, 0, j=0, k=-10)
    p.g3(0, 10, 0, j=10, k=0)
    p.g1(-3, 10, 0)
    p.g3(-3, 5, -5, j=-5, k=0)

    for g, name, axes in ((17, "xy", "XY"), (18, "xz", "XZ"), (19, "yz", "YZ")):
        p = new("h_arc_%s_radius" % name,
                "G%d arcs by positive R: the arc of at most 180 degrees, G2 and G3" % g)
        if g != 17:
            p.set_plane(g)
        a1, a2 = PLANES[g][1]

        def pt(u, v, w=0):
            q = [0.0, 0.0, 0.0]
            q[a1], q[a2], q[PLANES[g][2]] = u, v, w
            return q
        p.g0(*pt(0, -5))
        p.g1(*pt(0, 0), f=5)
        p.g2(*pt(20, 0), r=15, f=10)
        p.g3(*pt(40, 0), r=15)
        p.g3(*pt(40, 30), r=25)
        p.g2(*pt(10, 30), r=100)
        p.g3(*pt(10, 10), r=10.001)
        p.g2(*pt(0, 0), r=50, f=5)

        p = new("h_arc_%s_radius_negative" % name,
                "G%d arcs by negative R: rs274 takes the arc longer than 180 degrees" % g)
        if g != 17:
            p.set_plane(g)
        p.g0(*pt(0, -5))
        p.g1(*pt(0, 0), f=5)
        p.g2(*pt(20, 0), r=-15, f=10)
        p.g3(*pt(40, 0), r=-15)
        p.g3(*pt(40, 30), r=-25)
        p.g2(*pt(10, 30), r=-100)
        p.g2(*pt(10, 10), r=-10.001)

        p = new("h_full_circle_%s" % name, "G%d full circles by centre: end point = start point" % g)
        if g != 17:
            p.set_plane(g)
        p.g0(*pt(10, 0))
        letters = [CENTRE_WORDS[a1].lower(), CENTRE_WORDS[a2].lower()]

        def centre(u, v):
            d = {letters[0]: u, letters[1]: v}
            return d
        p.g2(*pt(10, 0), f=10, **centre(-10, 0))
        p.g3(*pt(10, 0), **centre(0, 5))
        p.g1(*pt(30, 0))
        p.g2(*pt(30, 0), **centre(3, -4))
        p.g3(*pt(30, 0), **centre(-0.05, 0))

        p = new("h_helix_%s" % name,
                "G%d helices: arcs by centre and by R with a move along the normal axis, one full turn" % g)
        if g != 17:
            p.set_plane(g)
        p.g0(*pt(10, 0, 5))
        p.g2(*pt(0, -10, 3), f=10, **centre(-10, 0))
        p.g3(*pt(0, 10, 1), **centre(0, 10))
        p.g2(*pt(0, 10, -4), **centre(0, -10))
        p.g3(*pt(20, 10, -6), r=12)
        p.g2(*pt(0, 10, -8), r=-12)

    p = new("h_arc_small", "tiny arcs: radius 0.1 mm, sweeps of a few degrees, a 0.05 mm full circle")
    p.g0(0, -1, 0)
    p.g1(0, 0, 0, f=5)
    p.g3(0.2, 0, i=0.1, j=0, f=1)
    p.g2(0.34, 0.02, i=0.08, j=-0.06)     # radius 0.1 with the 3-4-5 triangle, 90 degrees
    p.g1(50, 0.02)
    # radius 65 mm, from (63, 16) to (60, 25) about the centre: 8.4 degrees
    p.g3(47, 9.02, i=-63, j=-16)
    p.g2(50, 0.02, i=-60, j=-25)
    p.g2(50, 0.02, i=0.03, j=0.04)
    p.g3(50.05, 0.02, r=0.03)

    p = new("h_arc_large", "large arcs: 270 and 359 degree arcs by centre, a 500 mm radius, a 150 mm R arc")
    p.g0(0, -1, 0)
    p.g1(0, 0, 0, f=5)
    p.g2(10, 10, i=0, j=10, f=20)                        # 270 degrees clockwise
    p.g3(10, 10, i=-10, j=0)                             # full circle
    p.g1(0, 10)
    p.g3(300, 10, r=500)
    p.g2(0, 10, r=-160)
    # 65 mm circle from (65, 0) to (63, -16): 345.7 degrees counterclockwise
    p.g1(65, 100)
    p.g3(63, 84, i=-65, j=0)

    p = new("h_dwell", "dwells between moves: G4 P<s> in rs274, G4 T<s> in our dialect")
    p.g0(0, 0, 5)
    p.dwell("0.5")
    p.g1(0, 0, 0, f=2)
    p.dwell(2)
    p.g1(10, 0, 0)
    p.dwell("0.001")
    p.g3(20, 0, 0, i=5, j=0)
    p.dwell("1.25")
    p.g0(20, 0, 5)

    p = new("h_feed_changes", "feed changes on lines and arcs: rs274 F in mm/min is 60 x our F in mm/s")
    p.g0(0, -1, 0)
    p.g1(0, 0, 0, f=5)
    p.g1(10, 0, 0, f=1)
    p.g1(20, 0, 0, f=12.5)
    p.g2(30, 0, 0, i=5, j=0, f=100)
    p.g1(30, 10, 0, f="0.5")
    p.g1(30, 20, 0)
    p.g3(20, 20, 0, r=6, f=25)
    p.g1(0, 20, -1, f=250)

    p = new("h_g92_set_position", "G92 sets the current position without motion, in absolute mode only")
    p.g0(10, 10, 10)
    p.g1(20, 10, 10, f=10)
    p.set_position([0, 0, 0])
    p.g1(5, 5, 0)
    p.g2(15, 5, 0, i=5, j=0)
    p.set_position([mm(100), mm(-20), mm(3.5)])
    p.g1(110, -20, 3.5)
    p.g0(0, -1, 0)
    p.g1(0, 0, 0, f=5)
    p.set_position([mm(1), mm(2), mm(3)])
    p.g1(1, 2, 4)

    p = new("h_rounded_rectangle", "a closed contour of lines and tangent quarter arcs, counterclockwise")
    p.g0(10, 0, 0)
    p.g1(10, 0, -1, f=5)
    p.g1(50, 0, -1, f=20)
    p.g3(60, 10, i=0, j=10)
    p.g1(60, 30)
    p.g3(50, 40, i=-10, j=0)
    p.g1(10, 40)
    p.g3(0, 30, r=10)
    p.g1(0, 10)
    p.g3(10, 0, r=10)
    p.g0(10, 0, 5)

    p = new("h_mixed_planes", "arcs and helices while switching G17, G18, G19 and G90/G91")
    p.g0(0, -1, 0)
    p.g1(0, 0, 0, f=5)
    p.g2(10, 10, 0, i=10, j=0, f=10)
    p.set_plane(18)
    p.g3(20, 10, 10, i=10, k=0)
    p.set_plane(19)
    p.incremental()
    p.g2(20, 20, 0, j=10, k=0)
    p.set_plane(17)
    p.g3(30, 30, -5, r=10)
    p.absolute()
    p.set_plane(18)
    p.g2(30, 35, -15, r=-8)
    p.set_plane(17)
    p.g1(0, 0, 0)

    # ---- tool radius compensation
    # travelling clockwise, the left is the outside of the contour; counterclockwise, the inside
    p = new("h_comp_left_square_outside",
            "G41 around a square travelled clockwise: the tool outside, outside corners, line entry and exit")
    p.g0(-10, -10, 0)
    p.comp_on("L", mm(2))
    p.g1(0, 0, f=10)
    p.g1(0, 40)
    p.g1(40, 40)
    p.g1(40, 0)
    p.g1(0, 0)
    p.comp_off()
    p.g1(-10, -10)

    p = new("h_comp_right_square_inside",
            "G42 around a square travelled clockwise: the tool inside, inside corners")
    p.g0(20, 20, 0)
    p.comp_on("R", mm(3))
    p.g1(0, 20, f=10)
    p.g1(0, 40)
    p.g1(40, 40)
    p.g1(40, 0)
    p.g1(0, 0)
    p.g1(0, 20)
    p.comp_off()
    p.g1(20, 20)

    p = new("h_comp_left_pocket_rounded",
            "G41 in a rounded rectangle travelled counterclockwise: the tool inside, concave arcs of radius 10 > 4")
    p.g0(30, 20, 0)
    p.comp_on("L", mm(4))
    p.g1(30, 0, f=10)
    p.g1(50, 0)
    p.g3(60, 10, i=0, j=10)
    p.g1(60, 30)
    p.g3(50, 40, i=-10, j=0)
    p.g1(10, 40)
    p.g3(0, 30, i=0, j=-10)
    p.g1(0, 10)
    p.g3(10, 0, i=10, j=0)
    p.g1(30, 0)
    p.comp_off()
    p.g1(30, 20)

    p = new("h_comp_right_outside_rounded",
            "G42 around a rounded rectangle travelled counterclockwise: the tool outside, convex arcs")
    p.g0(30, -15, 0)
    p.comp_on("R", mm(2.5))
    p.g1(30, 0, f=10)
    p.g1(50, 0)
    p.g3(60, 10, r=10)
    p.g1(60, 30)
    p.g3(50, 40, r=10)
    p.g1(10, 40)
    p.g3(0, 30, r=10)
    p.g1(0, 10)
    p.g3(10, 0, r=10)
    p.g1(30, 0)
    p.comp_off()
    p.g1(30, -15)

    p = new("h_comp_arc_entry_exit", "G42 with an arc as the entry move and an arc before the exit line")
    p.g0(-20, -20, 0)
    p.comp_on("R", mm(2))
    p.g2(0, 0, r=20, f=10)
    p.g1(30, 0)
    p.g2(40, -10, i=0, j=-10)
    p.g1(40, -30)
    p.comp_off()
    p.g1(20, -40)

    p = new("h_comp_acute_corners",
            "G41 around a triangle with acute corners travelled clockwise, tool outside: rs274 rounds them with arcs")
    p.g0(-10, 0, 0)
    p.comp_on("L", mm(1.5))
    p.g1(0, 0, f=10)
    p.g1(15, 60)
    p.g1(30, 0)
    p.g1(0, 0)
    p.comp_off()
    p.g1(-10, 0)

    p = new("h_comp_obtuse_mixed",
            "G42 along an open zigzag contour with obtuse and reflex corners, lines and arcs, with Z moves")
    p.g0(0, -10, 5)
    p.g1(0, -10, -1, f=2)
    p.comp_on("R", mm(1))
    p.g1(0, 0, f=10)
    p.g1(20, 5)
    p.g1(40, 0)
    p.g2(60, 0, r=12)
    p.g1(70, 10)
    p.g3(90, 10, i=10, j=0)
    p.g1(100, 0)
    p.comp_off()
    p.g1(110, -10)
    p.g0(110, -10, 5)

    p = new("h_comp_incremental", "G41 with the contour written in G91 incremental coordinates")
    p.g0(-5, -5, 0)
    p.incremental()
    p.comp_on("L", mm(2))
    p.g1(0, 0, f=10)
    p.g1(30, 0)
    p.g3(30, 20, i=0, j=10)
    p.g1(0, 20)
    p.g1(0, 0)
    p.comp_off()
    p.g1(-5, -5)
    p.absolute()

    p = new("h_comp_tooltable_left",
            "G41 D1 with the radius from the tool table, tool 1 of radius 1 mm; our D is the radius itself")
    p.g0(-10, -10, 0)
    p.comp_on("L", TOOLS[1], tool=1)
    p.g1(0, 0, f=10)
    p.g1(0, 30)
    p.g2(30, 30, r=16)
    p.g1(30, 0)
    p.g1(0, 0)
    p.comp_off()
    p.g1(-10, -10)

    p = new("h_comp_tooltable_right",
            "G42 D3 with the radius from the tool table, tool 3 of radius 4 mm, and G42 D2 of 2.5 mm later")
    p.g0(-10, 20, 0)
    p.comp_on("R", TOOLS[3], tool=3)
    p.g1(0, 20, f=10)
    p.g1(0, 60)
    p.g1(60, 60)
    p.g1(60, 20)
    p.g1(0, 20)
    p.comp_off()
    p.g1(-10, 20)
    p.comp_on("R", TOOLS[2], tool=2)
    p.g1(0, 0)
    p.g3(40, 0, i=20, j=0)
    p.comp_off()
    p.g1(50, 0)

    return progs


# ---------------------------------------------------------------------------------------------
# random programs

def _lattice(c):
    return [(a, b) for a in range(-c, c + 1) for b in range(-c, c + 1) if a * a + b * b == c * c]


# integer radii with many integer points on their circle (Pythagorean triples), scaled by a
# number of micrometres: arcs by centre whose end point lies exactly on the circle
HYPOTENUSES = [5, 10, 13, 17, 25, 29, 65, 85]
LATTICE = {c: _lattice(c) for c in HYPOTENUSES}
SCALES = [20, 50, 100, 200, 250, 500, 1000]         # micrometres per lattice unit
FEEDS = ["2.5", "5", "10", "12.5", "20", "25", "50", "100"]
DWELLS = ["0.1", "0.25", "0.5", "1", "1.5", "2"]
BOX = 150000                                         # keep positions within +-150 mm


def _feed(rng, p, prob=0.3):
    if p.feed is None or rng.random() < prob:
        return rng.choice(FEEDS)
    return None


def _near(rng, p, span=40000):
    """a random point near the current one, pulled back towards the origin."""
    tgt = []
    for v in p.pos:
        d = rng.randrange(-span, span + 1)
        if abs(v + d) > BOX:
            d = -d
        tgt.append(v + d)
    return tgt


def _rand_line(rng, p, g=None):
    g = g or ("G0" if rng.random() < 0.2 else "G1")
    tgt = list(p.pos)
    k = rng.choice([1, 2, 2, 3, 3])
    near = _near(rng, p)
    for a in rng.sample([0, 1, 2], k):
        tgt[a] = near[a]
    if tgt == p.pos:
        tgt[0] += 1000
    p.move(g, tgt, None if g == "G0" else _feed(rng, p))


def _rand_centre_arc(rng, p, full=False, dz=0, radius_max=80000):
    name, (a1, a2), n = PLANES[p.plane]
    while True:
        c = rng.choice(HYPOTENUSES)
        s = rng.choice(SCALES)
        if 100 <= c * s <= radius_max:
            break
    pts = LATTICE[c]
    v0 = rng.choice(pts)
    v1 = v0 if full else rng.choice([v for v in pts if v != v0])
    centre = list(p.pos)
    centre[a1] -= s * v0[0]
    centre[a2] -= s * v0[1]
    tgt = list(p.pos)
    tgt[a1] = centre[a1] + s * v1[0]
    tgt[a2] = centre[a2] + s * v1[1]
    tgt[n] += dz
    p.arc(rng.choice(["G2", "G3"]), tgt, centre=centre, f=_feed(rng, p))


def _rand_radius_arc(rng, p, negative=False, dz=0):
    name, (a1, a2), n = PLANES[p.plane]
    while True:
        d1 = rng.randrange(-40000, 40001)
        d2 = rng.randrange(-40000, 40001)
        chord = math.hypot(d1, d2)
        if chord >= 2000 and abs(p.pos[a1] + d1) <= BOX and abs(p.pos[a2] + d2) <= BOX:
            break
    r = int(math.ceil(chord / 2 * rng.uniform(1.05, 4.0)))
    tgt = list(p.pos)
    tgt[a1] += d1
    tgt[a2] += d2
    tgt[n] += dz
    p.arc(rng.choice(["G2", "G3"]), tgt, r=-r if negative else r, f=_feed(rng, p))


def _start(rng, p):
    p.move("G0", [rng.randrange(-50000, 50001) for _ in range(3)])


def gen_lines(rng, p):
    _start(rng, p)
    for _ in range(rng.randrange(10, 20)):
        if rng.random() < 0.15:
            p.incremental() if not p.inc else p.absolute()
        _rand_line(rng, p)


def gen_centre_arcs(plane, helix=False):
    def gen(rng, p):
        if plane != 17:
            p.set_plane(plane)
        _start(rng, p)
        for _ in range(rng.randrange(8, 16)):
            x = rng.random()
            if x < 0.2:
                _rand_line(rng, p, g="G1")
            else:
                dz = rng.randrange(-20000, 20001) if helix and rng.random() < 0.7 else 0
                _rand_centre_arc(rng, p, full=rng.random() < 0.12, dz=dz)
            if rng.random() < 0.1:
                p.incremental() if not p.inc else p.absolute()
    return gen


def gen_radius_arcs(plane, negative):
    def gen(rng, p):
        if plane != 17:
            p.set_plane(plane)
        _start(rng, p)
        for _ in range(rng.randrange(8, 16)):
            if rng.random() < 0.2:
                _rand_line(rng, p, g="G1")
            else:
                dz = rng.randrange(-10000, 10001) if rng.random() < 0.25 else 0
                _rand_radius_arc(rng, p, negative=negative and rng.random() < 0.5, dz=dz)
            if rng.random() < 0.1:
                p.incremental() if not p.inc else p.absolute()
    return gen


def gen_mixed(rng, p):
    _start(rng, p)
    for _ in range(rng.randrange(14, 26)):
        x = rng.random()
        if x < 0.1:
            p.set_plane(rng.choice([g for g in PLANES if g != p.plane]))
        elif x < 0.18:
            p.incremental() if not p.inc else p.absolute()
        elif x < 0.23:
            p.dwell(rng.choice(DWELLS))
        elif x < 0.26 and not p.inc:
            p.set_position([rng.randrange(-50000, 50001) for _ in range(3)])
        elif x < 0.5:
            _rand_line(rng, p)
        elif x < 0.8:
            dz = rng.randrange(-15000, 15001) if rng.random() < 0.3 else 0
            _rand_centre_arc(rng, p, full=rng.random() < 0.08, dz=dz)
        else:
            _rand_radius_arc(rng, p, negative=rng.random() < 0.2)
    if p.plane != 17 and rng.random() < 0.5:
        p.set_plane(17)


def gen_comp(rng, p):
    """a closed star-shaped contour in XY with lines and R arcs, tool compensation on one side,
    entry from outside the contour by a line, exit by a line after G40."""
    r_tool = rng.choice([500, 1000, 1500, 2000, 2500, 3000, 4000])
    n = rng.randrange(3, 9)
    cx, cy = rng.randrange(-4000, 4001) * 10, rng.randrange(-4000, 4001) * 10
    while True:
        angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(n))
        gaps = [(angles[(i + 1) % n] - angles[i]) % (2 * math.pi) for i in range(n)]
        if min(gaps) > math.radians(25) and max(gaps) < math.radians(150):
            break
    verts = []
    for a in angles:
        rad = rng.uniform(20000, 60000)
        # on a 0.01 mm grid: every edge then has an exact interior point (the overrun below)
        verts.append([cx + 10 * int(round(rad * math.cos(a) / 10)), cy + 10 * int(round(rad * math.sin(a) / 10)), 0])
    if rng.random() < 0.5:
        verts.reverse()                    # clockwise
    side = rng.choice("LR")
    z = rng.choice([0, -1000, -2500])
    # entry: from a point away from the centroid beyond the first vertex
    v0 = verts[0]
    dx, dy = v0[0] - cx, v0[1] - cy
    d = math.hypot(dx, dy)
    out = rng.uniform(8000, 20000)
    entry = [v0[0] + int(round(dx / d * out)), v0[1] + int(round(dy / d * out)), z]
    p.move("G0", [entry[0], entry[1], 5000])
    p.move("G1", entry, rng.choice(FEEDS))
    if rng.random() < 0.2:
        p.incremental()
    p.comp_on(side, r_tool)
    p.move("G1", [v0[0], v0[1], z], _feed(rng, p, 0.2))
    first_is_line = True
    for i in range(n):
        a, b = verts[i], verts[(i + 1) % n]
        tgt = [b[0], b[1], z]
        if rng.random() < 0.35:
            chord = math.hypot(b[0] - a[0], b[1] - a[1])
            r = int(math.ceil(chord / 2 * rng.uniform(1.1, 3.0)))
            r = max(r, 3 * r_tool)
            if 4 * r * r > chord * chord:
                p.arc(rng.choice(["G2", "G3"]), tgt, r=r, f=_feed(rng, p, 0.2))
                first_is_line = first_is_line and i > 0
                continue
        p.move("G1", tgt, _feed(rng, p, 0.2))
    # mostly overrun the start along the first edge (exactly on it), so that the corner at the
    # first vertex is compensated too; otherwise the exit leaves from that vertex
    dx, dy = verts[1][0] - v0[0], verts[1][1] - v0[1]
    g = math.gcd(dx, dy)
    if first_is_line and g > 1 and rng.random() < 0.7:
        k = g // 2
        p.move("G1", [v0[0] + dx // g * k, v0[1] + dy // g * k, z])
    if not comp_corners_ok(p):
        raise ValueError("a corner that rs274 takes as straight")
    p.comp_off()
    p.move("G1", entry)
    if p.inc:
        p.absolute()
    p.move("G0", [entry[0], entry[1], 5000])


def _arc_centre_xy(e):
    """the centre (mm) of a programmed XY arc of Prog.expect, by centre or by R (the usual
    construction: on the chord's bisector, on the side given by the direction and R's sign)."""
    s = [v / 1000 for v in e["start"]]
    t = [v / 1000 for v in e["end"]]
    if e["centre"] is not None:
        return [v / 1000 for v in e["centre"][:2]]
    r = e["r"] / 1000
    dx, dy = t[0] - s[0], t[1] - s[1]
    chord = math.hypot(dx, dy)
    h = math.sqrt(max(r * r - chord * chord / 4, 0.0))
    sign = (1 if e["g"] == "G3" else -1) * (1 if r > 0 else -1)
    return [(s[0] + t[0]) / 2 - sign * h * dy / chord, (s[1] + t[1]) / 2 + sign * h * dx / chord]


def _tangents_xy(e):
    """unit directions of travel (XY) at the start and at the end of a programmed element."""
    s = [v / 1000 for v in e["start"]]
    t = [v / 1000 for v in e["end"]]
    if e["g"] in ("G0", "G1"):
        d = math.hypot(t[0] - s[0], t[1] - s[1])
        u = ((t[0] - s[0]) / d, (t[1] - s[1]) / d)
        return u, u
    c = _arc_centre_xy(e)
    k = 1 if e["g"] == "G3" else -1

    def tan(q):
        rx, ry = q[0] - c[0], q[1] - c[1]
        d = math.hypot(rx, ry)
        return (-k * ry / d, k * rx / d)
    return tan(s), tan(t)


def comp_corners_ok(p, small=0.06):
    """rs274 treats a corner between compensated elements that turns by less than 0.05 rad
    (TOLERANCE_CONCAVE_CORNER) as straight: neither intersected nor rounded, which leaves the
    tool up to r (1 - cos 0.05) off the exact offset path. Keep the random contours clear of
    such corners (tangent joins, turn 0, are exact and allowed)."""
    lines = sorted(l for l, e in p.expect.items() if e["compensated"])
    for l0, l1 in zip(lines, lines[1:]):
        if l1 != l0 + 1:
            continue
        _, a = _tangents_xy(p.expect[l0])
        b, _ = _tangents_xy(p.expect[l1])
        turn = abs(math.atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]))
        if 1e-9 < turn < small:
            return False
    return True


def random_specs():
    """(name, description, generator) of the random programs."""
    specs = []
    for i in range(8):
        specs.append(("r_lines_%02d" % i, "random G0/G1 lines, G90/G91 switches, feed changes", gen_lines))
    for g, name in ((17, "xy"), (18, "xz"), (19, "yz")):
        for i in range(5):
            specs.append(("r_arcs_%s_%02d" % (name, i),
                          "random G%d arcs by centre with exact end points, some full circles, lines" % g,
                          gen_centre_arcs(g)))
        for i in range(3):
            specs.append(("r_helix_%s_%02d" % (name, i),
                          "random G%d helices by centre, some full turns" % g, gen_centre_arcs(g, helix=True)))
        for i in range(3):
            specs.append(("r_radius_%s_%02d" % (name, i),
                          "random G%d arcs by positive R, some helical, and lines" % g,
                          gen_radius_arcs(g, negative=False)))
        specs.append(("r_radius_negative_%s_00" % name,
                      "random G%d arcs by R, about half negative: longer than 180 degrees" % g,
                      gen_radius_arcs(g, negative=True)))
    for i in range(15):
        specs.append(("r_mixed_%02d" % i,
                      "random mix: planes, G90/G91, lines, arcs, helices, dwells, G92, feeds", gen_mixed))
    for i in range(20):
        specs.append(("r_comp_%02d" % i,
                      "random closed contour with tool radius compensation, lines and R arcs", gen_comp))
    return specs


# ---------------------------------------------------------------------------------------------
# running rs274

TRACE_CHILD = r"""
import json, sys
sys.path.insert(0, %(dist)r)
import gcode

class Canon:
    parameter_file = sys.argv[2]
    def __init__(self):
        self.line = 0
        self.ev = []
        self.plane = 1
    def _e(self, *a):
        self.ev.append([self.line] + list(a))
    def next_line(self, st):
        self.line = st.sequence_number
    def set_plane(self, pl):
        self.plane = pl
        self._e("PLANE", pl)
    def set_feed_rate(self, f):
        self._e("FEED", f)
    def _xyz(self, kind, a):
        if any(v != 0.0 for v in a[3:]):
            self._e("OTHER", kind + " with A B C U V W")
        self._e(kind, a[0], a[1], a[2])
    def straight_traverse(self, *a):
        self._xyz("TRAVERSE", a)
    def straight_feed(self, *a):
        self._xyz("LINE", a)
    def arc_feed(self, fe, se, fa, sa, rot, ae, *rest):
        if any(v != 0.0 for v in rest):
            self._e("OTHER", "ARC with A B C U V W")
        self._e("ARC", self.plane, fe, se, fa, sa, rot, ae)
    def dwell(self, t):
        self._e("DWELL", t)
    def set_g92_offset(self, *a):
        self._e("G92OFFSET", a[0], a[1], a[2])
    def set_g5x_offset(self, index, *a):
        if any(v not in (0.0, None) for v in a):
            self._e("OTHER", "G5x offset")
    def set_xy_rotation(self, t):
        if t != 0.0:
            self._e("OTHER", "XY rotation")
    def comment(self, s):
        self._e("COMMENT", s)
    def message(self, s):
        self._e("OTHER", "MESSAGE " + s)
    def get_tool(self, idx):
        return (-1, 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0)
    def get_external_length_units(self):
        return 1.0
    def get_external_angular_units(self):
        return 1.0
    def get_axis_mask(self):
        return 7
    def get_block_delete(self):
        return False
    def check_abort(self):
        return False
    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        def f(*a):
            self._e("OTHER", name)
        return f

c = Canon()
res = gcode.parse(sys.argv[1], c, sys.argv[3], "G17 G90")
json.dump({"result": res[0], "last_line": res[1], "events": c.ev}, sys.stdout)
"""

# which fields (after line and kind) of each event are lengths or feeds, i.e. handed over by
# the module divided by 25.4 when the program runs in millimetres
LENGTH_FIELDS = {"TRAVERSE": (0, 1, 2), "LINE": (0, 1, 2), "ARC": (1, 2, 3, 4, 6),
                 "G92OFFSET": (0, 1, 2), "FEED": (0,)}


def run_module(ngc_path, tmp, units):
    var = os.path.join(tmp, "module.var")
    open(var, "w").close()
    code = TRACE_CHILD % {"dist": DIST_PACKAGES}
    pr = subprocess.run([SYS_PYTHON, "-c", code, ngc_path, var, units], capture_output=True, text=True, cwd=tmp)
    if pr.returncode != 0 or not pr.stdout.startswith("{"):
        return None, "python module: rc %d %s" % (pr.returncode, pr.stderr.strip()[-400:])
    out = json.loads(pr.stdout)
    if out["result"] != 1:      # INTERP_EXIT (M2) is success
        return None, "python module: result %d at line %d" % (out["result"], out["last_line"])
    return out["events"], None


def exact_events(mm_events, inch_events):
    """The module hands a G21 program's lengths and feeds over divided by 25.4 (it works in
    inches), which loses the interpreter's exact doubles. The interpreter itself computes in
    program units, so the same program read in G20 gives those doubles undivided. Accept the
    G20 values only if the two runs have the same events and every G20 length v satisfies
    v / 25.4 == the G21 value bit for bit (the division the module does)."""
    if len(mm_events) != len(inch_events):
        return None, "G21 and G20 runs differ: %d vs %d events" % (len(mm_events), len(inch_events))
    out = []
    for a, b in zip(mm_events, inch_events):
        if a[:2] != b[:2] or len(a) != len(b):
            return None, "G21 and G20 runs differ: %r vs %r" % (a, b)
        lengths = LENGTH_FIELDS.get(a[1], ())
        for i, (x, y) in enumerate(zip(a[2:], b[2:])):
            if i in lengths:
                if y / 25.4 != x:
                    return None, "G21 and G20 runs differ: %r vs %r" % (a, b)
            elif x != y:
                return None, "G21 and G20 runs differ: %r vs %r" % (a, b)
        out.append(b)
    return out, None


BIN_RE = re.compile(r"^\s*\d+ N\S* (\w+)\((.*)\)\s*$")


def run_binary(ngc_path, tmp, tool_table):
    var = os.path.join(tmp, "binary.var")
    open(var, "w").close()
    cmd = [RS274, "-g", "-v", var]
    if tool_table:
        # the standalone rs274's canon reports inches as the machine unit and converts the tool
        # table from inches: hand it tool.tbl's millimetre diameters divided by 25.4
        tbl = os.path.join(tmp, "tool_inch.tbl")
        with open(tbl, "w") as f:
            for t, r in sorted(TOOLS.items()):
                f.write("T%d P%d D%r ;radius %s mm\n" % (t, t, 2 * r / 1000 / 25.4, fmt(r)))
        cmd += ["-t", tbl]
    pr = subprocess.run(cmd + [ngc_path], capture_output=True, text=True, cwd=tmp)
    if pr.returncode != 0:
        return None, "rs274: rc %d: %s" % (pr.returncode, (pr.stderr + pr.stdout).strip()[-400:])
    calls = []
    for ln in pr.stdout.splitlines():
        m = BIN_RE.match(ln)
        if m:
            calls.append((m.group(1), m.group(2)))
    return calls, None


def binary_motions(calls):
    out = []
    for name, args in calls:
        if name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "DWELL"):
            out.append((name, [float(a) for a in args.split(",")]))
    return out


def module_motions(events):
    out = []
    for e in events:
        k = e[1]
        if k == "TRAVERSE":
            out.append(("STRAIGHT_TRAVERSE", e[2:5]))
        elif k == "LINE":
            out.append(("STRAIGHT_FEED", e[2:5]))
        elif k == "ARC":
            out.append(("ARC_FEED", [e[3], e[4], e[5], e[6], e[7], e[8]]))
        elif k == "DWELL":
            out.append(("DWELL", [e[2]]))
    return out


def cross_check(mod_events, calls):
    a, b = module_motions(mod_events), binary_motions(calls)
    if len(a) != len(b):
        return "the module gave %d motions, the binary %d" % (len(a), len(b))
    for i, ((ka, va), (kb, vb)) in enumerate(zip(a, b)):
        if ka != kb:
            return "motion %d: %s vs %s" % (i, ka, kb)
        for x, y in zip(va, vb):
            if abs(x - y) > BIN_TOLERANCE + 1e-12 * abs(x):
                return "motion %d %s: %r vs %r" % (i, ka, va, vb)
    return None


def run_rs274(prog, tmp):
    """run it three ways; return (events, None) or (None, error)."""
    ngc, _ = prog.texts()
    path = os.path.join(tmp, prog.name + ".ngc")
    with open(path, "w") as f:
        f.write(ngc)
    calls, err = run_binary(path, tmp, prog.tool_table)
    if err:
        return None, err
    if prog.tool_table:
        # the Python module cannot read a tool table outside a running LinuxCNC (its tool data
        # lives in shared memory): run the same program with G41.1/G42.1 D<diameter>
        mod_path = os.path.join(tmp, prog.name + ".module.ngc")
        with open(mod_path, "w") as f:
            f.write(re.sub(r"^(G4[12]) D(\d+)$",
                           lambda m: "%s.1 D%s" % (m.group(1), fmt(2 * TOOLS[int(m.group(2))])),
                           ngc, flags=re.M))
        path = mod_path
    mm_events, err = run_module(path, tmp, "G21")
    if err:
        return None, err
    with open(path) as f:
        text = f.read()
    inch_path = path[:-4] + ".inch.ngc"
    assert "\nG21 G91.1 " in text
    with open(inch_path, "w") as f:
        f.write(text.replace("\nG21 G91.1 ", "\nG20 G91.1 ", 1))
    inch_events, err = run_module(inch_path, tmp, "G20")
    if err:
        return None, err
    events, err = exact_events(mm_events, inch_events)
    if err:
        return None, err
    err = cross_check(events, calls)
    if err:
        return None, "module/binary mismatch: " + err
    return events, None


# ---------------------------------------------------------------------------------------------
# the trace file

COMP_COMMENTS = {"interpreter: cutter radius compensation on left": "LEFT",
                 "interpreter: cutter radius compensation on right": "RIGHT",
                 "interpreter: cutter radius compensation off": "OFF"}
IGNORED_COMMENTS = ("interpreter: distance mode changed to",)


def check_element(prog, line, kind, end, ctr, plane, rot):
    """an element outside tool compensation must be exactly what its block programs."""
    exp = prog.expect.get(line)
    if exp is None or exp["compensated"]:
        return
    want_kind = {"G0": "TRAVERSE", "G1": "LINE", "G2": "ARC", "G3": "ARC"}[exp["g"]]
    bad = []
    if kind != want_kind:
        bad.append("kind %s, programmed %s" % (kind, exp["g"]))
    if any(abs(a - b / 1000) > 1e-9 for a, b in zip(end, exp["end"])):
        bad.append("end %r, programmed %r" % (end, exp["end"]))
    if kind == "ARC" and not exp["exit"]:
        name, (a1, a2), nrm = PLANES[exp["plane"]]
        if plane != name:
            bad.append("plane %s, programmed %s" % (plane, name))
        if rot != (-1 if exp["g"] == "G2" else 1):
            bad.append("rotation %d for %s" % (rot, exp["g"]))
        st = [v / 1000 for v in exp["start"]]
        if exp["centre"] is not None:
            if any(abs(ctr[a] - exp["centre"][a] / 1000) > 1e-9 for a in (a1, a2)):
                bad.append("centre %r, programmed %r" % (ctr, exp["centre"]))
        else:
            r = abs(exp["r"]) / 1000
            for q in (st, end):
                if abs(math.hypot(q[a1] - ctr[a1], q[a2] - ctr[a2]) - r) > 1e-9:
                    bad.append("centre %r not at R from %r" % (ctr, q))
            sweep = arc_sweep(st, end, ctr, a1, a2, rot)
            if (sweep > math.pi) != (exp["r"] < 0):
                bad.append("sweep %.6f rad for R %s" % (sweep, fmt(exp["r"])))
    if bad:
        raise RuntimeError("%s line %d: %s" % (prog.name, line, "; ".join(bad)))


def arc_sweep(start, end, ctr, a1, a2, rot):
    """the angle an arc turns through (radians, (0, 2 pi]), rot > 0 counterclockwise in (a1, a2)."""
    t0 = math.atan2(start[a2] - ctr[a2], start[a1] - ctr[a1])
    t1 = math.atan2(end[a2] - ctr[a2], end[a1] - ctr[a1])
    d = (t1 - t0) if rot > 0 else (t0 - t1)
    d %= 2 * math.pi
    return d if d > 1e-12 else 2 * math.pi


def trace_text(prog, events):
    last = HEADER_LINES + len(prog.blocks) + 1          # the M2 line
    out = ["# rs274 trace of %s: %s" % (prog.name, prog.desc),
           "# programs: ngc/%s.ngc (rs274), din/%s.cnc (DIN 66025); format: README.md" % (prog.name, prog.name)]
    pos = [0.0, 0.0, 0.0]
    g92 = [0.0, 0.0, 0.0]
    out.append("START %s %s %s" % tuple(num(v) for v in pos))
    n_el = 0
    per_line = {}
    for e in events:
        line, kind = e[0], e[1]
        if line <= HEADER_LINES or line >= last:
            if kind in ("TRAVERSE", "LINE", "ARC", "DWELL"):
                raise RuntimeError("%s: motion on line %d" % (prog.name, line))
            continue
        if kind in ("TRAVERSE", "LINE"):
            pos = [e[2], e[3], e[4]]
            check_element(prog, line, kind, pos, None, None, None)
            out.append("%s %d %s %s %s" % ((kind, line) + tuple(num(v) for v in pos)))
        elif kind == "ARC":
            g = CANON_PLANE[e[2]]
            name, (a1, a2), nrm = PLANES[g]
            end = [0.0] * 3
            ctr = [0.0] * 3
            end[a1], end[a2], ctr[a1], ctr[a2], rot, end[nrm] = e[3], e[4], e[5], e[6], e[7], e[8]
            ctr[nrm] = pos[nrm]
            check_element(prog, line, kind, end, ctr, name, rot)
            pos = end
            out.append("ARC %d %s %s %s %s %s %s %s %d" % ((line,) + tuple(num(v) for v in end + ctr) + (name, rot)))
        elif kind == "DWELL":
            out.append("DWELL %d %s" % (line, num(e[2])))
        elif kind == "FEED":
            f = Decimal(num(e[2]))
            per_s = f / 60
            if per_s * 60 != f:
                raise RuntimeError("%s: feed %s not exact in units/s" % (prog.name, f))
            out.append("FEED %d %s %s" % (line, num(e[2]), fmt_dec(per_s)))
        elif kind == "PLANE":
            out.append("PLANE %d %s" % (line, PLANES[CANON_PLANE[e[2]]][0]))
        elif kind == "G92OFFSET":
            new = e[2:5]
            derived = [p + o - q for p, o, q in zip(pos, g92, new)]
            want = [v / 1000 for v in prog.setpos[line]]
            if any(abs(d - w) > 1e-9 for d, w in zip(derived, want)):
                raise RuntimeError("%s: G92 on line %d: rs274 gives %r, program %r" % (prog.name, line, derived, want))
            g92 = new
            pos = want
            out.append("SETPOS %d %s %s %s" % ((line,) + tuple(num(v) for v in pos)))
        elif kind == "COMMENT":
            if e[2] in COMP_COMMENTS:
                what = COMP_COMMENTS[e[2]]
                if what == "OFF":
                    out.append("COMP %d OFF" % line)
                else:
                    side, r = prog.comp_radius[line]
                    assert (side == "L") == (what == "LEFT")
                    out.append("COMP %d %s %s" % (line, what, num(r / 1000)))
            elif e[2].startswith(IGNORED_COMMENTS) or not e[2].startswith("interpreter:"):
                pass
            else:
                raise RuntimeError("%s: unexpected comment %r" % (prog.name, e[2]))
        else:
            raise RuntimeError("%s: unexpected canon call %r" % (prog.name, e))
        if kind in ("TRAVERSE", "LINE", "ARC", "DWELL"):
            n_el += 1
            per_line[line] = per_line.get(line, 0) + 1
    for line, exp in prog.expect.items():
        if not exp["compensated"] and per_line.get(line) != 1:
            raise RuntimeError("%s line %d: %s elements" % (prog.name, line, per_line.get(line)))
    return "\n".join(out) + "\n", n_el


# ---------------------------------------------------------------------------------------------
# the corpus


def rs274_version():
    pr = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", PACKAGE], capture_output=True, text=True)
    return pr.stdout.strip() if pr.returncode == 0 else "unknown"


def build_corpus(out_dir, tmp, log=sys.stderr):
    progs = hand_written()
    results = []
    for p in progs:
        ev, err = run_rs274(p, tmp)
        if err:
            raise SystemExit("hand-written program %s refused: %s" % (p.name, err))
        results.append((p, ev, 1))
    for name, desc, gen in random_specs():
        rng = random.Random(name)
        for attempt in range(1, 101):
            p = Prog(name, "random", desc)
            try:
                gen(rng, p)
            except ValueError:
                continue
            ev, err = run_rs274(p, tmp)
            if not err:
                break
        else:
            raise SystemExit("%s: no program accepted by rs274 in 100 draws (last: %s)" % (name, err))
        if attempt > 1:
            print("%s: draw %d accepted" % (name, attempt), file=log)
        results.append((p, ev, attempt))

    for sub in ("ngc", "din", "trace"):
        os.makedirs(os.path.join(out_dir, sub), exist_ok=True)
    index = ["# rs274 reference corpus (generated by tools/rs274_fixtures.py; do not edit)",
             "# rs274: %s %s (/usr/bin/rs274 and its Python module gcode)" % (PACKAGE, rs274_version()),
             "# name kind elements draws flags | description"]
    total_el = total_lines = 0
    for p, ev, attempt in results:
        ngc, din = p.texts()
        text, n_el = trace_text(p, ev)
        with open(os.path.join(out_dir, "ngc", p.name + ".ngc"), "w") as f:
            f.write(ngc)
        with open(os.path.join(out_dir, "din", p.name + ".cnc"), "w") as f:
            f.write(din)
        with open(os.path.join(out_dir, "trace", p.name + ".txt"), "w") as f:
            f.write(text)
        total_el += n_el
        total_lines += sum(1 for ln in text.splitlines() if not ln.startswith("#"))
        index.append("%s %s %d %d %s | %s" % (p.name, p.kind, n_el, attempt, ",".join(sorted(p.flags)), p.desc))
    index.append("# %d programs, %d motion elements and dwells, %d trace lines" % (len(results), total_el, total_lines))
    with open(os.path.join(out_dir, "index.txt"), "w") as f:
        f.write("\n".join(index) + "\n")
    with open(os.path.join(out_dir, "tool.tbl"), "w") as f:
        f.write("; tool table (LinuxCNC format, millimetres) of the h_comp_tooltable_* programs: G41/G42 D<tool>\n")
        for t, r in sorted(TOOLS.items()):
            f.write("T%d P%d D%s ;radius %s mm\n" % (t, t, fmt(2 * r), fmt(r)))
    return len(results), total_el, total_lines


def compare_dirs(a, b):
    diffs = []
    for sub in ("", "ngc", "din", "trace"):
        da, db = os.path.join(a, sub), os.path.join(b, sub)
        fa = {f for f in os.listdir(da) if os.path.isfile(os.path.join(da, f))} if os.path.isdir(da) else set()
        fb = {f for f in os.listdir(db) if os.path.isfile(os.path.join(db, f))} if os.path.isdir(db) else set()
        if sub == "":
            fa.discard("README.md")
            fb.discard("README.md")
        for f in sorted(fa ^ fb):
            diffs.append("only in %s: %s" % (a if f in fa else b, os.path.join(sub, f)))
        for f in sorted(fa & fb):
            if not filecmp.cmp(os.path.join(da, f), os.path.join(db, f), shallow=False):
                diffs.append("differs: %s" % os.path.join(sub, f))
    return diffs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=DEFAULT_OUT, help="corpus directory (default tests/cnc/rs274)")
    ap.add_argument("--check", action="store_true", help="regenerate in a temp dir and compare with --out")
    ap.add_argument("--list", action="store_true", help="print the program names")
    args = ap.parse_args()
    if args.list:
        for p in hand_written():
            print(p.name)
        for name, _, _ in random_specs():
            print(name)
        return 0
    for path in (RS274, SYS_PYTHON):
        if not os.path.exists(path):
            print("rs274_fixtures: %s not found (apt-get install -y %s)" % (path, PACKAGE), file=sys.stderr)
            return 2
    with tempfile.TemporaryDirectory(prefix="rs274_") as tmp:
        if args.check:
            gen_dir = os.path.join(tmp, "corpus")
            work = os.path.join(tmp, "work")
            os.makedirs(work)
            build_corpus(gen_dir, work)
            diffs = compare_dirs(args.out, gen_dir)
            for d in diffs:
                print(d)
            print("rs274_fixtures --check: %s" % ("%d difference(s)" % len(diffs) if diffs else "up to date"))
            return 1 if diffs else 0
        n, el, lines = build_corpus(args.out, tmp)
        print("rs274_fixtures: %d programs, %d elements, %d trace lines -> %s" % (n, el, lines, args.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
