#!/usr/bin/env python3
"""Generate a large, valid IEC 61131-3 Structured Text project (strict `iec` dialect).

    gen_project.py OUTDIR [--lines N] [--seed S]

Writes OUTDIR/project.toml and OUTDIR/src/*.st (files of ~1000-2000 lines):
global variable lists, TYPEs, FUNCTIONs, FUNCTION_BLOCKs with METHODs, PROGRAMs and a
CONFIGURATION with two tasks, about N lines in all (default 30000), and prints the
total line count.  The output depends only on N and the seed.

The code is type-correct for the strict dialect (docs/dialect.md): no narrowing, no
INT<->BOOL, no integer<->bit-string mixes, only the implicit widenings of the IEC table,
explicit *_TO_* conversions otherwise.  Every call uses existing parameters of matching
types, POUs only call POUs generated before them (no recursion), every FUNCTION and
METHOD with a result assigns it, and locals that end up unreferenced are not declared.

Importable: `generate(lines) -> dict[filename, content]` (filenames relative to OUTDIR,
e.g. "project.toml", "src/fbs_01.st").

The class `Gen` is also the core of tools/gen_codesys23_export.py (mode "codesys").
"""
import argparse
import os
import random
import re
import sys

DEFAULT_SEED = 61131

# ----------------------------------------------------------------------------- type facts
INT_RANGE = {
    'SINT': (-128, 127), 'INT': (-32768, 32767), 'DINT': (-2 ** 31, 2 ** 31 - 1),
    'USINT': (0, 255), 'UINT': (0, 65535), 'UDINT': (0, 2 ** 32 - 1),
}
LIT_MAX = {'SINT': 100, 'INT': 1000, 'DINT': 100000, 'USINT': 200, 'UINT': 1000, 'UDINT': 100000}
SIGNED = ('SINT', 'INT', 'DINT')
UNSIGNED = ('USINT', 'UINT', 'UDINT')
INTS = SIGNED + UNSIGNED
BITSTR = ('BYTE', 'WORD', 'DWORD')
BIT_WIDTH = {'BYTE': 8, 'WORD': 16, 'DWORD': 32}
REALS = ('REAL', 'LREAL')
NUMERIC = INTS + REALS

# IEC implicit conversions (target <- sources), docs/dialect.md
IMPLICIT = {
    'INT': ['SINT', 'USINT'],
    'DINT': ['SINT', 'INT', 'USINT', 'UINT'],
    'UINT': ['USINT'],
    'UDINT': ['USINT', 'UINT'],
    'REAL': ['SINT', 'INT', 'USINT', 'UINT'],
    'LREAL': ['INT', 'DINT', 'UINT', 'UDINT', 'REAL'],
    'WORD': ['BYTE'],
    'DWORD': ['BYTE', 'WORD'],
}

# explicit conversions: target -> [(function, source)]
CONV = {
    'INT': [('REAL_TO_INT', 'REAL'), ('DINT_TO_INT', 'DINT'), ('WORD_TO_INT', 'WORD'),
            ('BYTE_TO_INT', 'BYTE'), ('UINT_TO_INT', 'UINT'), ('BOOL_TO_INT', 'BOOL'),
            ('STRING_TO_INT', 'STRING'), ('LREAL_TO_INT', 'LREAL')],
    'DINT': [('REAL_TO_DINT', 'REAL'), ('DWORD_TO_DINT', 'DWORD'), ('INT_TO_DINT', 'INT'),
             ('UDINT_TO_DINT', 'UDINT'), ('LREAL_TO_DINT', 'LREAL'), ('STRING_TO_DINT', 'STRING')],
    'SINT': [('INT_TO_SINT', 'INT')],
    'USINT': [('BYTE_TO_USINT', 'BYTE'), ('INT_TO_USINT', 'INT')],
    'UINT': [('INT_TO_UINT', 'INT'), ('WORD_TO_UINT', 'WORD'), ('DINT_TO_UINT', 'DINT')],
    'UDINT': [('DINT_TO_UDINT', 'DINT'), ('DWORD_TO_UDINT', 'DWORD')],
    'REAL': [('INT_TO_REAL', 'INT'), ('DINT_TO_REAL', 'DINT'), ('UDINT_TO_REAL', 'UDINT'),
             ('LREAL_TO_REAL', 'LREAL')],
    'LREAL': [('REAL_TO_LREAL', 'REAL'), ('DINT_TO_LREAL', 'DINT')],
    'BYTE': [('INT_TO_BYTE', 'INT'), ('WORD_TO_BYTE', 'WORD'), ('USINT_TO_BYTE', 'USINT')],
    'WORD': [('INT_TO_WORD', 'INT'), ('DWORD_TO_WORD', 'DWORD'), ('UINT_TO_WORD', 'UINT'),
             ('BYTE_TO_WORD', 'BYTE')],
    'DWORD': [('DINT_TO_DWORD', 'DINT'), ('WORD_TO_DWORD', 'WORD'), ('UDINT_TO_DWORD', 'UDINT')],
    'STRING': [('INT_TO_STRING', 'INT'), ('DINT_TO_STRING', 'DINT'), ('REAL_TO_STRING', 'REAL'),
               ('UINT_TO_STRING', 'UINT')],
    'BOOL': [],
    'TIME': [],
}

KEYWORDS = """ABSTRACT ACTION END_ACTION AND AND_THEN ARRAY AT BY CASE END_CASE CONFIGURATION
END_CONFIGURATION CONSTANT CONTINUE DO ELSE ELSIF END_FOR END_IF END_REPEAT END_WHILE EXIT EXTENDS
FALSE FINAL FOR FUNCTION END_FUNCTION FUNCTION_BLOCK END_FUNCTION_BLOCK END_GET END_SET IF
IMPLEMENTS INTERFACE END_INTERFACE INTERNAL JMP METHOD END_METHOD MOD NAMESPACE END_NAMESPACE
NON_RETAIN NOT OF ON OR OR_ELSE PERSISTENT POINTER PRIVATE PROGRAM END_PROGRAM PROPERTY
END_PROPERTY PROTECTED PUBLIC REFERENCE REF_TO REPEAT RESOURCE END_RESOURCE RETAIN RETURN STRUCT
END_STRUCT SUPER TASK THEN THIS TO TRUE TYPE END_TYPE UNION END_UNION UNTIL VAR VAR_ACCESS
VAR_CONFIG VAR_EXTERNAL VAR_GLOBAL VAR_INPUT VAR_IN_OUT VAR_INST VAR_OUTPUT VAR_STAT VAR_TEMP
END_VAR WHILE WITH XOR REF GET SET S R T D DT TOD LT
BOOL BIT SINT INT DINT LINT USINT UINT UDINT ULINT BYTE WORD DWORD LWORD REAL LREAL TIME LTIME
DATE LDATE TIME_OF_DAY LTOD DATE_AND_TIME LDT STRING WSTRING CHAR WCHAR
ABS SQRT SIN COS TAN ASIN ACOS ATAN LN LOG EXP EXPT ADD SUB MUL DIV MOVE MIN MAX LIMIT SEL MUX
SHL SHR ROL ROR LEN LEFT RIGHT MID CONCAT INSERT DELETE REPLACE FIND ADR SIZEOF BITADR TRUNC
TON TOF TP R_TRIG F_TRIG CTU CTD CTUD SR RS PLC_PRG""".split()

WORDS = """Motor Axis Valve Pump Conveyor Temp Press Level Flow Speed Pos Torque Heater Fan Door Lamp
Alarm Msg Recipe Batch Step Cycle Count Limit Offset Gain Filter Ramp Scale Buffer Queue Crc Sum Timer
Delay Pulse Mode State Cmd Status Error Warn Enable Done Busy Ready Active Valid Index Value Avg Total
Last Next Prev Target Actual Setpoint Tank Mixer Dosing Weight Belt Gripper Robot Station Clamp Sensor
Switch Drive Encoder Brake Lube Oil Water Air Vacuum Cooler Zone Line Cell Feeder Sorter Label Printer
Scanner Barcode Job Order Shift Energy Power Current Voltage Freq Humidity Dose Hold Jog Home Park
Purge Fill Drain Heat Cool Stir Wash Dry Cut Weld Lift Hopper Silo Screw Spindle Tool Magazine Loader
Pallet Carrier Lane Gate Bridge Hoist Trolley Winch Roller Nozzle Burner Boiler Chiller Compressor
Blower Damper Filler Capper Sealer Wrapper Palletizer Stacker Dryer Oven Kiln Furnace Extruder""".split()

ENUM_VALUES = """IDLE INIT READY RUN STOP ERROR HOMING JOG AUTO MANUAL WAIT DONE ABORT RESET FILL
DRAIN HEAT COOL OPEN CLOSE MOVE HOLD STARTUP SHUTDOWN PAUSE SERVICE CLEAN CALIB""".split()

PFX = {'BOOL': 'b', 'INT': 'i', 'DINT': 'di', 'SINT': 'si', 'USINT': 'usi', 'UINT': 'ui',
       'UDINT': 'udi', 'REAL': 'r', 'LREAL': 'lr', 'BYTE': 'by', 'WORD': 'w', 'DWORD': 'dw',
       'TIME': 't', 'STRING': 's'}

STD_FB_PFX = {'TON': 'ton', 'TOF': 'tof', 'TP': 'tp', 'R_TRIG': 'rt', 'F_TRIG': 'ft',
              'CTU': 'ctu', 'CTD': 'ctd', 'SR': 'sr', 'RS': 'rs'}

STR_LENS = [1, 4, 8, 10, 12, 16, 20, 24, 32, 40, 50, 64, 80, 100, 128, 200, 255]
TIME_LITS = ['T#10ms', 'T#20ms', 'T#50ms', 'T#100ms', 'T#250ms', 'T#500ms', 'T#1s', 'T#2s',
             'T#5s', 'T#10s', 'T#30s', 'T#1m', 'T#1m30s', 'T#2m', 'T#1h', 'T#1s500ms']
TEXTS_ASCII = ['Start', 'Stop', 'Fault', 'Ready', 'Running', 'Idle', 'Axis ', 'Pump ', 'OK', 'NOK',
               'Error: ', 'Warning', 'Step ', 'Batch', 'Recipe', 'Temp', 'Level low', 'Level high',
               'Door open', 'E-Stop', 'Homing', 'Done', 'Timeout', ' / ', ': ', '-', 'x', 'Valve',
               'Motor overload', 'Pressure', 'mbar', 'degC', 'Line$N', 'Tab$T']
COMMENTS_ASCII = ['check the limits first', 'ramp the setpoint', 'reset on rising edge',
                  'copy values into the table', 'build the status text', 'wait for the feedback',
                  'scale raw value to engineering units', 'simple state machine',
                  'watchdog for the feedback signal', 'count the good parts',
                  'filter the analog input', 'pack status bits into a word', 'search the table',
                  'handle the alarm acknowledge', 'only in automatic mode', 'temperature in degC',
                  'TODO: tune the gain on site', 'keep the last valid value']


# ----------------------------------------------------------------------------- model
class Ty:
    """A type: kind is scalar | string | enum | struct | array | fb | ptr."""

    def __init__(self, kind, name=None, decl=None, **kw):
        self.kind = kind
        self.name = name
        self.decl = decl or name
        self.length = kw.get('length')
        self.elem = kw.get('elem')
        self.dims = kw.get('dims')          # [(lo_txt, lo, hi_txt, hi)]
        self.members = kw.get('members')    # [(name, Ty)]
        self.values = kw.get('values')      # [(name, int)]
        self.fb = kw.get('fb')              # PouInfo
        self.target = kw.get('target')
        if kind == 'scalar':
            self.key = name
        elif kind == 'string':
            self.key = 'STRING'
        elif kind == 'enum':
            self.key = 'ENUM:' + name
        elif kind == 'ptr':
            self.key = 'PTR:' + target_key(self.target)
        else:
            self.key = kind.upper() + ':' + self.decl


_STRIP = re.compile(r"\(\*|\*\)|//[^\n]*|'(?:\$.|[^'$\n])*'|\"(?:\$.|[^\"$\n])*\"")
_TOK = re.compile(r"[A-Za-z_]\w*|\d[\w#]*(?:\.\d\w*)?|:=|=>|\.\.|[().#]")


def ident_set(lines):
    """Lower-case identifiers referenced in ST text: no comments, strings, .members,
    enum values after '#', or formal parameter names (`name :=` / `name =>` inside a call)."""
    text = '\n'.join(lines)
    out, depth, pos = [], 0, 0
    for m in _STRIP.finditer(text):
        t = m.group(0)
        if depth == 0:
            out.append(text[pos:m.start()])
        if t == '(*':
            depth += 1
        elif t == '*)':
            depth = max(0, depth - 1)
        out.append(' ')
        pos = m.end()
    if depth == 0:
        out.append(text[pos:])
    toks = _TOK.findall(''.join(out))
    res, par = set(), 0
    for i, t in enumerate(toks):
        if t == '(':
            par += 1
        elif t == ')':
            par -= 1
        elif t[0].isalpha() or t[0] == '_':
            if i and toks[i - 1] in ('.', '#'):
                continue
            if par > 0 and i + 1 < len(toks) and toks[i + 1] in (':=', '=>'):
                continue
            res.add(t.lower())
    return res


def is_literal(t):
    return t[:1].isdigit() or t[:1] == "'" or t in ('TRUE', 'FALSE') or t[:2] in ('T#', 'T#')


def target_key(t):
    return t.key if t is not None else '?'


SCALAR = {n: Ty('scalar', n) for n in ('BOOL',) + INTS + BITSTR + REALS + ('TIME',)}
T_BOOL = SCALAR['BOOL']
_STRINGS = {}


def string_ty(n):
    if n not in _STRINGS:
        _STRINGS[n] = Ty('string', 'STRING', 'STRING(%d)' % n, length=n)
    return _STRINGS[n]


class Var:
    WRITABLE = ('local', 'out', 'inout', 'global', 'loop_w')

    def __init__(self, name, ty, role, init=None, comment=None):
        self.name = name
        self.ty = ty
        self.role = role        # in inconst out inout local loop global gconst external
        self.init = init
        self.comment = comment
        self.used = False
        self.writable = role in Var.WRITABLE
        self.bind = {}          # inout parameter -> bound variable (FB instances)
        self._pats = None

    def patterns(self):
        """Access paths to scalar/string/enum values: (segments, Ty, writable)."""
        if self._pats is None:
            out = []

            def walk(segs, ty, depth, wr):
                k = ty.kind
                if k in ('scalar', 'string', 'enum'):
                    out.append((segs, ty, wr))
                    if k == 'scalar' and ty.name in BIT_WIDTH and depth <= 2:
                        out.append((segs + [('bit', BIT_WIDTH[ty.name])], T_BOOL, wr))
                elif k == 'struct' and depth < 3:
                    for m, mt in ty.members:
                        walk(segs + ['.' + m], mt, depth + 1, wr)
                elif k == 'array' and depth < 3:
                    walk(segs + [('idx', ty.dims)], ty.elem, depth + 1, wr)
                elif k == 'fb' and depth < 2:
                    for o, ot in ty.fb.outputs:
                        if ot.kind in ('scalar', 'string', 'enum'):
                            out.append((segs + ['.' + o], ot, False))
            walk([self.name], self.ty, 0, self.writable)
            self._pats = out
        return self._pats


class PouInfo:
    def __init__(self, kind, name):
        self.kind = kind
        self.name = name
        self.inputs = []     # [(name, Ty)]
        self.inconst = []
        self.outputs = []
        self.inouts = []
        self.ret = None
        self.actions = []
        self.methods = []    # [PouInfo]
        self.owner = None

    def params(self):
        return self.inputs + self.inconst + self.inouts

    def simple(self):
        return not self.inouts and all(t.kind in ('scalar', 'string', 'enum') for _, t in self.params())


def std_fbs():
    def mk(name, ins, outs):
        p = PouInfo('fb', name)
        p.inputs = [(n, SCALAR[t]) for n, t in ins]
        p.outputs = [(n, SCALAR[t]) for n, t in outs]
        return p
    res = {}
    for n in ('TON', 'TOF', 'TP'):
        res[n] = mk(n, [('IN', 'BOOL'), ('PT', 'TIME')], [('Q', 'BOOL'), ('ET', 'TIME')])
    for n in ('R_TRIG', 'F_TRIG'):
        res[n] = mk(n, [('CLK', 'BOOL')], [('Q', 'BOOL')])
    res['CTU'] = mk('CTU', [('CU', 'BOOL'), ('RESET', 'BOOL'), ('PV', 'INT')], [('Q', 'BOOL'), ('CV', 'INT')])
    res['CTD'] = mk('CTD', [('CD', 'BOOL'), ('LOAD', 'BOOL'), ('PV', 'INT')], [('Q', 'BOOL'), ('CV', 'INT')])
    res['SR'] = mk('SR', [('SET1', 'BOOL'), ('RESET', 'BOOL')], [('Q1', 'BOOL')])
    res['RS'] = mk('RS', [('SET', 'BOOL'), ('RESET1', 'BOOL')], [('Q1', 'BOOL')])
    return {n: Ty('fb', n, fb=p) for n, p in res.items()}


class Scope:
    def __init__(self, parent=None):
        self.parent = parent
        self.vars = []
        self.dirty = True
        self.idx_r = {}
        self.idx_w = {}

    def add(self, v):
        self.vars.append(v)
        self.dirty = True
        return v

    def remove(self, v):
        self.vars.remove(v)
        self.dirty = True

    def _build(self):
        self.idx_r, self.idx_w = {}, {}
        for v in self.vars:
            byk, byk_w = {}, {}
            for p in v.patterns():
                byk.setdefault(p[1].key, []).append(p)
                if p[2]:
                    byk_w.setdefault(p[1].key, []).append(p)
            for k, ps in byk.items():
                self.idx_r.setdefault(k, []).append((v, ps))
            for k, ps in byk_w.items():
                self.idx_w.setdefault(k, []).append((v, ps))
        self.dirty = False

    def cands(self, key, writable):
        if self.dirty:
            self._build()
        own = (self.idx_w if writable else self.idx_r).get(key, [])
        if self.parent is None:
            return own
        return own + self.parent.cands(key, writable)

    def keys(self, writable):
        if self.dirty:
            self._build()
        ks = list((self.idx_w if writable else self.idx_r).keys())
        if self.parent is not None:
            for k in self.parent.keys(writable):
                if k not in ks:
                    ks.append(k)
        return ks

    def all_vars(self):
        s, out = self, []
        while s is not None:
            out.extend(s.vars)
            s = s.parent
        return out


# ----------------------------------------------------------------------------- generator core
class Gen:
    ROLE_ORDER = [('in', 'VAR_INPUT'), ('inconst', 'VAR_INPUT CONSTANT'), ('out', 'VAR_OUTPUT'),
                  ('inout', 'VAR_IN_OUT'), ('external', 'VAR_EXTERNAL'),
                  ('extconst', 'VAR_EXTERNAL CONSTANT'), ('local', 'VAR'), ('loop', 'VAR')]

    def __init__(self, mode='iec', seed=DEFAULT_SEED):
        self.mode = mode
        self.cs = mode == 'codesys'
        self.rng = random.Random(seed)
        self.I = '\t' if self.cs else '    '
        self.BI = '' if self.cs else self.I     # indent of POU bodies
        self.names = set(k.lower() for k in KEYWORDS)
        self.root = Scope()
        self.consts = {}
        self.const_list = []
        self.enums, self.structs, self.arrays = [], [], []
        self.funcs, self.funcs_by_ret = [], {}
        self.fbs, self.programs = [], []
        self.std = std_fbs()
        self.maxd = 2
        self.local_bias = 0.8
        self.texts = TEXTS_ASCII
        self.comments = COMMENTS_ASCII
        self.conv = {k: list(v) for k, v in CONV.items()}
        self.stats = {'FUNCTION': 0, 'FUNCTION_BLOCK': 0, 'PROGRAM': 0, 'METHOD': 0, 'ACTION': 0,
                      'TYPE': 0}
        # per-body state
        self.scope = self.root
        self.decl_scope = self.root
        self.pset = set()
        self.loops = []          # (name, lo, hi) of active loops
        self.loop_kinds = []
        self.loop_busy = []
        self.allow_gw = True
        self.used_globals = []

    # ------------------------------------------------------------------ names
    def uniq(self, base, local=False):
        n, k = base, 1
        while n.lower() in self.names or n.lower() in self.pset:
            k += 1
            n = '%s%d' % (base, k)
        (self.pset if local else self.names).add(n.lower())
        return n

    def word(self):
        return self.rng.choice(WORDS)

    def words(self, n=None):
        n = n or self.rng.choice([1, 1, 2, 2, 2, 3])
        return ''.join(self.word() for _ in range(n))

    def pou_name(self, pfx):
        return self.uniq(pfx + self.words(self.rng.choice([1, 2, 2, 3])))

    # ------------------------------------------------------------------ types
    def rand_scalar_name(self, numeric_bias=False):
        w = [('BOOL', 6), ('INT', 6), ('DINT', 3), ('REAL', 5), ('WORD', 2), ('DWORD', 1.5),
             ('BYTE', 1.2), ('UINT', 1), ('UDINT', 0.6), ('SINT', 0.4), ('USINT', 0.5),
             ('LREAL', 0.6), ('TIME', 2), ('STRING', 1.8)]
        if numeric_bias:
            w = [(n, x * (2 if n in NUMERIC else 0.5)) for n, x in w]
        return self.rng.choices([n for n, _ in w], [x for _, x in w])[0]

    def rand_scalar(self, numeric_bias=False, max_str=None):
        n = self.rand_scalar_name(numeric_bias)
        if n == 'STRING':
            lens = [l for l in STR_LENS if (l >= 8 or self.rng.random() < 0.3) and (max_str is None or l <= max_str)]
            return string_ty(self.rng.choice(lens))
        return SCALAR[n]

    def const_dim(self, lo=0):
        c = self.rng.choice([c for c in self.const_list if self.consts[c] <= 64])
        v = self.consts[c]
        return ('%d' % lo, lo, '%s-1' % c if lo == 0 else c, v - 1 if lo == 0 else v)

    def array_ty(self, elem, dims):
        rng = ', '.join('%s..%s' % (d[0], d[2]) for d in dims)
        return Ty('array', None, 'ARRAY[%s] OF %s' % (rng, elem.decl), elem=elem, dims=dims)

    def prefix(self, ty):
        if ty.kind in ('scalar', 'string'):
            return PFX[ty.name]
        if ty.kind == 'enum':
            return 'e'
        if ty.kind == 'struct':
            return 'st'
        if ty.kind == 'array':
            return 'a' + self.prefix(ty.elem)
        if ty.kind == 'fb':
            return STD_FB_PFX.get(ty.name, 'fb')
        if ty.kind == 'ptr':
            return 'p' + self.prefix(ty.target) if ty.target.kind != 'array' else 'pa'
        return 'x'

    def var_name(self, ty, word=None):
        return self.uniq(self.prefix(ty) + (word or self.words(self.rng.choice([1, 1, 2]))), local=True)

    def gen_constants(self):
        spec = [('MAX_ITEMS', 16), ('MAX_AXES', 8), ('BUF_SIZE', 64), ('MAX_MSG', 10),
                ('MAX_STEPS', 20), ('MAX_ZONES', 4), ('TABLE_LEN', 32), ('MAX_RECIPES', 12),
                ('HIST_LEN', 24), ('MAX_STATIONS', 6)]
        vs = []
        for n, val in spec:
            self.names.add(n.lower())
            self.consts[n] = val
            self.const_list.append(n)
            vs.append(self.root.add(Var(n, SCALAR['INT'], 'gconst', str(val))))
        extra = [('C_PI', 'REAL', '3.1415927'), ('C_GRAVITY', 'REAL', '9.81'),
                 ('C_TIMEOUT', 'TIME', 'T#5s'), ('C_MAX_TEMP', 'REAL', '120.0'),
                 ('C_VERSION', string_ty(16), "'V1.4.2'"), ('C_MASK_LOW', 'WORD', '16#00FF'),
                 ('C_DEFAULT_SPEED', 'INT', '1500'), ('C_MAX_PRESSURE', 'LREAL', '250.5')]
        for n, t, val in extra:
            self.names.add(n.lower())
            ty = t if isinstance(t, Ty) else SCALAR[t]
            vs.append(self.root.add(Var(n, ty, 'gconst', val)))
        return vs

    def gen_enum(self):
        w = self.word()
        name = self.uniq('E_' + w + self.rng.choice(['State', 'Mode', 'Cmd', 'Step', 'Phase']))
        p = w.upper()[:3]
        vals, v = [], self.rng.choice([0, 0, 1, 10])
        k = self.rng.randint(3, 7)
        for base in self.rng.sample(ENUM_VALUES, k):
            vn = self.uniq('%s_%s' % (p, base))
            vals.append((vn, v))
            v += self.rng.choice([1, 1, 5, 10])
        t = Ty('enum', name, values=vals)
        self.enums.append(t)
        self.stats['TYPE'] += 1
        return t

    def gen_struct(self):
        name = self.uniq('ST_' + self.words(self.rng.choice([1, 2])))
        mem, seen = [], set()
        for _ in range(self.rng.randint(3, 8)):
            r = self.rng.random()
            if r < 0.08 and self.enums:
                mt = self.rng.choice(self.enums)
            elif r < 0.16 and self.structs:
                mt = self.rng.choice(self.structs)
            elif r < 0.26 and self.const_list:
                mt = self.array_ty(self.rand_scalar(True, 40), [self.const_dim()])
            elif r < 0.29 and self.cs:
                mt = Ty('ptr', None, 'POINTER TO BYTE', target=SCALAR['BYTE'])
            else:
                mt = self.rand_scalar()
            base = self.prefix(mt) + self.word()
            mn, k = base, 1
            while mn.lower() in seen or mn.lower() in self.names:
                k += 1
                mn = '%s%d' % (base, k)
            seen.add(mn.lower())
            mem.append((mn, mt))
        t = Ty('struct', name, members=mem)
        t.inits = {}
        for mn, mt in mem:
            if self.rng.random() < 0.2 and mt.kind in ('scalar', 'string'):
                t.inits[mn] = self.literal(mt.key, mt.length)
        self.structs.append(t)
        self.stats['TYPE'] += 1
        return t

    def struct_init(self, t):
        mem = [(mn, mt) for mn, mt in t.members if mt.kind in ('scalar', 'string')]
        pick = self.rng.sample(mem, min(len(mem), self.rng.randint(1, 3)))
        return '(%s)' % ', '.join('%s := %s' % (mn, self.literal(mt.key, mt.length)) for mn, mt in pick)

    def gen_alias_array(self):
        name = self.uniq('T_' + self.words(1) + self.rng.choice(['Table', 'Buffer', 'List', 'Array', 'Vec']))
        r = self.rng.random()
        if r < 0.3 and self.structs:
            elem = self.rng.choice(self.structs)
        else:
            elem = self.rand_scalar(True, 32)
        dims = [self.const_dim(self.rng.choice([0, 0, 1]))]
        inner = self.array_ty(elem, dims)
        t = Ty('array', None, name, elem=elem, dims=dims)
        t.alias_of = inner.decl
        self.arrays.append(t)
        self.stats['TYPE'] += 1
        return t

    def type_text(self, t):
        """TYPE block for one type (IEC style; the CODESYS generator overrides it)."""
        I = self.I
        if t.kind == 'enum':
            vals = ', '.join('%s := %d' % v for v in t.values)
            c = self.rng.random()
            tail = ''
            if c < 0.2:
                tail = ' INT'                                   # typed enum
            elif c < 0.4:
                tail = ' := %s' % self.rng.choice(t.values)[0]  # default value
            return ['TYPE', '%s%s : (%s)%s;' % (I, t.name, vals, tail), 'END_TYPE']
        if t.kind == 'struct':
            lines = ['TYPE', '%s%s :' % (I, t.name), I + 'STRUCT']
            for mn, mt in t.members:
                init = ' := %s' % t.inits[mn] if mn in t.inits else ''
                lines.append('%s%s%s : %s%s;' % (I, I, mn, mt.decl, init))
            return lines + [I + 'END_STRUCT;', 'END_TYPE']
        return ['TYPE', '%s%s : %s;' % (I, t.decl, t.alias_of), 'END_TYPE']

    # ------------------------------------------------------------------ references
    def ref(self, key, writable=False, simple=False):
        """Pick a readable (or writable) access path of type `key`; returns (text, Ty)."""
        c = self.scope.cands(key, writable)
        if writable and not self.allow_gw:
            c = [x for x in c if x[0].role != 'global']
        if simple:
            c = [(v, [p for p in ps if len(p[0]) == 1]) for v, ps in c]
            c = [x for x in c if x[1]]
        if not c:
            return None
        loc = [x for x in c if x[0].role not in ('global', 'gconst')]
        if loc and (len(loc) == len(c) or self.rng.random() < self.local_bias):
            c = loc
        elif loc:
            c = [x for x in c if x[0].role in ('global', 'gconst')]
        v, ps = self.rng.choice(c)
        p = self.rng.choice(ps)
        self.use(v)
        return self.inst(p[0]), p[1]

    def use(self, v):
        v.used = True
        if v.role in ('global', 'gconst') and v not in self.used_globals:
            self.used_globals.append(v)
        return v.name

    def inst(self, segs):
        out = []
        for s in segs:
            if type(s) is str:
                out.append(s)
            elif s[0] == 'idx':
                out.append('[' + ', '.join(self.index(d) for d in s[1]) + ']')
            else:
                out.append('.%d' % self.rng.randrange(s[1]))
        return ''.join(out)

    def index(self, d):
        lo_t, lo, hi_t, hi = d
        cover = [l for l in self.loops if l[1] >= lo and l[2] <= hi]
        if cover and self.rng.random() < 0.8:
            return self.rng.choice(cover)[0]
        if self.rng.random() < 0.12:
            r = self.ref('INT', simple=True)
            if r:
                return 'LIMIT(%s, %s, %s)' % (lo_t, r[0], hi_t)
        return str(self.rng.randint(lo, hi))

    # ------------------------------------------------------------------ literals
    def literal(self, key, slen=None):
        r = self.rng
        if key == 'BOOL':
            return r.choice(['TRUE', 'FALSE'])
        if key in LIT_MAX:
            m = LIT_MAX[key]
            return str(r.choice([0, 1, 2, 5, 10, r.randint(0, m), r.randint(0, m // 10 or 1)]))
        if key == 'BYTE':
            return r.choice(['16#%02X' % r.randrange(256), str(r.randrange(256))])
        if key == 'WORD':
            return r.choice(['16#%04X' % r.randrange(65536), '16#00FF', '16#FF00', str(r.randrange(1000))])
        if key == 'DWORD':
            return r.choice(['16#%08X' % r.randrange(2 ** 32), '16#0000FFFF', str(r.randrange(100000))])
        if key in REALS:
            return r.choice(['%d.%d' % (r.randint(0, 500), r.randint(0, 99)), '0.5', '1.0', '100.0',
                             '%d.0E-3' % r.randint(1, 9), '2.5E2', '0.%02d' % r.randint(1, 99)])
        if key == 'TIME':
            return r.choice(TIME_LITS)
        if key == 'STRING':
            lim = slen or 20
            txt = [t for t in self.texts if len(t.replace('$', '')) <= lim]
            return "'%s'" % (r.choice(txt) if txt else 'Abcdefgh'[:lim])
        if key.startswith('ENUM:'):
            t = self.enum_by_key(key)
            return self.enum_lit(t, r.choice(t.values)[0])
        raise ValueError(key)

    def enum_by_key(self, key):
        for t in self.enums:
            if t.key == key:
                return t
        raise KeyError(key)

    def enum_lit(self, t, v):
        if not self.cs and self.rng.random() < 0.5:
            return '%s#%s' % (t.name, v)
        return v

    # ------------------------------------------------------------------ expressions
    def expr(self, key, d=0, conv=False, slen=None, top=True):
        if key.startswith('ENUM:') or key.startswith('PTR:'):
            return self.leaf(key, conv, slen, d)
        pl = 0.45 if d == 0 else 0.7
        if d >= self.maxd or self.rng.random() < pl:
            return self.leaf(key, conv, slen, d)
        res = self.composite(key, d, slen)
        if res is None:
            return self.leaf(key, conv, slen, d)
        txt, binary = res
        return '(%s)' % txt if binary and not top else txt

    def leaf(self, key, conv, slen, d):
        r = self.rng.random()
        if conv and r < 0.12 and key in IMPLICIT:
            t = self.ref(self.rng.choice(IMPLICIT[key]))
            if t:
                return t[0]
        if r < 0.68:
            t = self.ref(key)
            if t:
                return t[0]
        if r < 0.76 and self.conv.get(key) and d <= self.maxd:
            fn, src = self.rng.choice(self.conv[key])
            t = self.ref(src)
            if t:
                return '%s(%s)' % (fn, t[0])
            if src == 'STRING':
                return "%s('%d')" % (fn, self.rng.randint(0, 99))
            return '%s(%s)' % (fn, self.literal(src))
        if r < 0.84 and d < self.maxd:
            f = self.fcall(key, d)
            if f:
                return f
        if key.startswith('PTR:'):
            raise ValueError('no pointer in scope')
        if key == 'BOOL' and self.rng.random() < 0.85:
            txt, _ = self.compare(d + 1)
            return '(%s)' % txt
        return self.literal(key, slen)

    def fcall(self, key, d):
        fl = self.funcs_by_ret.get(key)
        if not fl:
            return None
        f = self.rng.choice(fl[-25:] if self.rng.random() < 0.6 else fl)
        args = [(n, self.expr(t.key, d + 1, True, t.length, True)) for n, t in f.params()]
        return self.call_text(f.name, args)

    def call_text(self, name, args):
        if self.cs:
            return '%s(%s)' % (name, ', '.join(a for _, a in args))
        return '%s(%s)' % (name, ', '.join('%s := %s' % (n, a) for n, a in args))

    def composite(self, key, d, slen):
        r = self.rng
        dd = d + 1

        def sub(k=key, top=False, sl=None):
            return self.expr(k, dd, False, sl if sl is not None else slen, top)

        def lhs(k=key, top=False):
            # left operand of a binary operator / first operand of a generic function:
            # avoid literal-op-literal and all-literal generic calls
            t = sub(k, top)
            if is_literal(t):
                rr = self.ref(k)
                if rr:
                    return rr[0]
            return t

        def conv():
            opts = self.conv.get(key)
            if not opts:
                return None
            fn, src = r.choice(opts)
            a = self.expr(src, dd, False, None, True) if src != 'STRING' else (
                (self.ref('STRING') or ("'%d'" % r.randint(0, 999),))[0])
            return '%s(%s)' % (fn, a), False

        def call():
            f = self.fcall(key, d)
            return (f, False) if f else None

        if key in SIGNED or key in UNSIGNED:
            lo_l = 0
            hi_l = LIT_MAX[key]
            c = r.randrange(16 if key == 'INT' else 14)
            if c == 0 or c == 1:
                return '%s + %s' % (lhs(), sub()), True
            if c == 2:
                return '%s - %s' % (lhs(), sub()), True
            if c == 3:
                return '%s * %d' % (lhs(), r.randint(2, 5)), True
            if c == 4:
                return '%s / %d' % (lhs(), r.randint(2, 9)), True
            if c == 5:
                return '%s MOD %d' % (lhs(), r.randint(2, 9)), True
            if c == 6:
                return '%s(%s, %s)' % (r.choice(['MIN', 'MAX']), lhs(top=True), sub(top=True)), False
            if c == 7:
                a = r.randint(lo_l, hi_l // 2)
                return 'LIMIT(%d, %s, %d)' % (a, lhs(top=True), r.randint(a + 1, hi_l)), False
            if c == 8:
                return 'SEL(%s, %s, %s)' % (self.expr('BOOL', dd), lhs(top=True), sub(top=True)), False
            if c == 9:
                return conv()
            if c == 10 or c == 11:
                return call()
            if c == 12:
                if key in SIGNED:
                    return 'ABS(%s)' % lhs(top=True), False
                return 'MAX(%s, %s)' % (lhs(top=True), sub(top=True)), False
            if c == 13:
                k = self.ref('INT', simple=True)
                sel = 'LIMIT(0, %s, 2)' % k[0] if k else '1'
                return 'MUX(%s, %s, %s, %s)' % (sel, lhs(top=True), sub(top=True), sub(top=True)), False
            if c == 14:
                return 'LEN(%s)' % self.expr('STRING', dd), False
            return 'FIND(%s, %s)' % (self.expr('STRING', dd), self.literal('STRING', 4)), False
        if key in BITSTR:
            c = r.randrange(10)
            if c < 3:
                return '%s %s %s' % (lhs(), r.choice(['AND', 'OR', 'XOR']), sub()), True
            if c == 3:
                return 'NOT %s' % lhs(), True
            if c < 7:
                return '%s(%s, %d)' % (r.choice(['SHL', 'SHR', 'ROL', 'ROR']), lhs(top=True),
                                       r.randint(1, BIT_WIDTH[key] - 1)), False
            if c < 9:
                return conv()
            return call()
        if key in REALS:
            c = r.randrange(14)
            if c < 2:
                return '%s + %s' % (lhs(), sub()), True
            if c == 2:
                return '%s - %s' % (lhs(), sub()), True
            if c == 3:
                return '%s * %s' % (lhs(), sub()), True
            if c == 4:
                return '%s / %d.%d' % (lhs(), r.randint(1, 20), r.randint(1, 9)), True
            if c == 5:
                return 'ABS(%s)' % lhs(top=True), False
            if c == 6:
                return 'SQRT(ABS(%s))' % lhs(top=True), False
            if c == 7:
                return '%s(%s)' % (r.choice(['SIN', 'COS']), lhs(top=True)), False
            if c == 8:
                return '%s(%s, %s)' % (r.choice(['MIN', 'MAX']), lhs(top=True), sub(top=True)), False
            if c == 9:
                return 'LIMIT(0.0, %s, %d.0)' % (lhs(top=True), r.randint(1, 1000)), False
            if c == 10 or c == 11:
                return conv()
            if c == 12:
                return call()
            return '-%s' % sub(), True
        if key == 'BOOL':
            c = r.randrange(10)
            if c < 4:
                return self.compare(dd)
            if c < 7:
                return '%s %s %s' % (lhs(), r.choice(['AND', 'AND', 'OR', 'OR', 'XOR']), sub()), True
            if c == 7:
                return 'NOT %s' % sub(), True
            if c == 8:
                return conv() or call()
            return call()
        if key == 'STRING':
            c = r.randrange(11)
            s = lambda: self.expr('STRING', dd, False, None, True)
            n = lambda: str(r.randint(1, 8))
            if c < 3:
                return 'CONCAT(%s, %s)' % (s(), s()), False
            if c == 3:
                return 'LEFT(%s, %s)' % (s(), n()), False
            if c == 4:
                return 'RIGHT(%s, %s)' % (s(), n()), False
            if c == 5:
                return 'MID(%s, %s, %s)' % (s(), n(), n()), False
            if c == 6:
                return 'INSERT(%s, %s, %s)' % (s(), s(), n()), False
            if c == 7:
                return 'DELETE(%s, %s, %s)' % (s(), n(), n()), False
            if c == 8:
                return 'REPLACE(%s, %s, %s, %s)' % (s(), s(), n(), n()), False
            if c == 9:
                return conv()
            return call()
        if key == 'TIME':
            c = r.randrange(6)
            if c < 2:
                return '%s + %s' % (lhs(), r.choice(TIME_LITS)), True
            if c == 2:
                return '%s - %s' % (lhs(), sub()), True
            if c == 3:
                return conv() or call()
            if c == 4:
                return 'SEL(%s, %s, %s)' % (self.expr('BOOL', dd), lhs(top=True), sub(top=True)), False
            return call()
        return None

    def compare(self, dd):
        r = self.rng
        avail = [k for k in self.scope.keys(False)
                 if k in NUMERIC or k in BITSTR or k in ('TIME', 'STRING') or k.startswith('ENUM:')]
        k = r.choice(avail) if avail else 'INT'
        left = self.ref(k)
        left = left[0] if left else self.expr(k, dd, False, None, False)
        if k in NUMERIC or k == 'TIME':
            ops = ['<', '>', '<=', '>='] + ([] if k in REALS else ['=', '<>'])
        else:
            ops = ['=', '<>']
        right = self.expr(k, dd + 1, False, None, False) if r.random() < 0.5 else self.literal(k, 8)
        if right == left:
            right = self.literal(k, 8)
        return '%s %s %s' % (left, r.choice(ops), right), True

    def cond(self):
        return self.expr('BOOL', 0, False, None, True)

    # ------------------------------------------------------------------ declarations
    def new_var(self, ty, role='local', word=None, init=None, comment=None, scope=None):
        v = Var(self.var_name(ty, word), ty, role, init, comment)
        (scope or self.decl_scope).add(v)
        return v

    def acquire_loop(self):
        for v in self.decl_scope.vars:
            if v.role == 'loop' and v not in self.loop_busy:
                self.loop_busy.append(v)
                return v
        names = ['i', 'j', 'k', 'n', 'm', 'x']
        used = sum(1 for v in self.decl_scope.vars if v.role == 'loop')
        base = names[used] if used < len(names) else 'iLoop'
        v = Var(self.uniq(base, local=True), SCALAR['INT'], 'loop')
        self.decl_scope.add(v)
        self.loop_busy.append(v)
        return v

    def release_loop(self, v):
        self.loop_busy.remove(v)

    # ------------------------------------------------------------------ statements
    def comment_line(self, ind):
        c = self.rng.choice(self.comments)
        if not self.cs and self.rng.random() < 0.6:
            return '%s// %s' % (ind, c)
        return '%s(* %s *)' % (ind, c)

    def end(self, kw):
        return kw if self.cs else kw + ';'

    def block(self, n, ind, d):
        out = []
        for _ in range(n):
            out += self.stmt(ind, d)
        return out

    def stmt(self, ind, d):
        r = self.rng
        inloop = bool(self.loop_kinds)
        opts = [('assign', 7.0)]
        if d < 2:
            opts += [('if', 2.2), ('case', 0.6), ('for', 0.7), ('while', 0.25), ('repeat', 0.25)]
        if self.fb_instances():
            opts.append(('fbcall', 0.5))
        if inloop:
            opts.append(('exit', 0.25))
            if not self.cs and self.loop_kinds[-1] == 'for':
                opts.append(('continue', 0.2))
        opts.append(('comment', 0.25))
        for _ in range(4):
            kind = r.choices([o for o, _ in opts], [w for _, w in opts])[0]
            res = getattr(self, 's_' + kind)(ind, d)
            if res:
                return res
        return res

    def s_comment(self, ind, d):
        return [self.comment_line(ind)] + self.s_assign(ind, d)

    def assign_keys(self):
        ks = [k for k in self.scope.keys(True) if not k.startswith('PTR:')]
        if not self.allow_gw:
            ks = [k for k in ks if any(v.role != 'global' for v, _ in self.scope.cands(k, True))]
        return ks

    def s_assign(self, ind, d, key=None):
        ks = self.assign_keys()
        if key is None:
            if not ks:
                return []
            w = [3 if k in ('BOOL', 'INT', 'REAL', 'DINT') else 1 for k in ks]
            key = self.rng.choices(ks, w)[0]
        t = self.ref(key, writable=True)
        if t is None:
            return []
        tgt, ty = t
        rhs = self.expr(key, 0, True, ty.length, True)
        if rhs == tgt:
            rhs = self.expr(key, 0, True, ty.length, True)
            if rhs == tgt:
                rhs = self.literal(key, ty.length)
        return ['%s%s := %s;' % (ind, tgt, rhs)]

    def s_if(self, ind, d):
        r = self.rng
        I = self.I
        out = ['%sIF %s THEN' % (ind, self.cond())] + self.block(r.randint(1, 3), ind + I, d + 1)
        for _ in range(r.choice([0, 0, 0, 1, 1, 2])):
            out += ['%sELSIF %s THEN' % (ind, self.cond())] + self.block(r.randint(1, 2), ind + I, d + 1)
        if r.random() < 0.4:
            out += ['%sELSE' % ind] + self.block(r.randint(1, 2), ind + I, d + 1)
        return out + [ind + self.end('END_IF')]

    def case_labels(self, lo, hi):
        r = self.rng
        labels, v = [], lo
        for _ in range(r.randint(2, 5)):
            if v > hi:
                break
            c = r.random()
            if c < 0.6 or v + 1 > hi:
                labels.append(str(v))
                v += r.randint(1, 3)
            elif c < 0.8:
                labels.append('%d, %d' % (v, v + 1))
                v += r.randint(2, 4)
            else:
                e = min(hi, v + r.randint(1, 4))
                labels.append('%d..%d' % (v, e))
                v = e + r.randint(1, 3)
        return labels

    def s_case(self, ind, d):
        r = self.rng
        I = self.I
        enums = [k for k in self.scope.keys(False) if k.startswith('ENUM:')]
        if enums and r.random() < 0.4:
            k = r.choice(enums)
            sel = self.ref(k)[0]
            t = self.enum_by_key(k)
            vals = r.sample(t.values, r.randint(1, len(t.values)))
            labels = [self.enum_lit(t, v[0]) for v in sorted(vals, key=lambda x: x[1])]
        else:
            ks = [k for k in ('INT', 'DINT', 'UINT', 'USINT', 'SINT') if self.scope.cands(k, False)]
            if not ks:
                return self.s_if(ind, d)
            k = r.choice(ks)
            sel = self.ref(k)[0]
            labels = self.case_labels(0, 100 if k in ('SINT', 'USINT') else 200)
        out = ['%sCASE %s OF' % (ind, sel)]
        for lab in labels:
            out += ['%s%s:' % (ind + I, lab)] + self.block(r.randint(1, 2), ind + I + I, d + 1)
        if r.random() < 0.5:
            out += ['%sELSE' % (ind + I)] + self.block(1, ind + I + I, d + 1)
        return out + [ind + self.end('END_CASE')]

    def top_arrays(self, writable=False, elem_keys=None, ndims=1):
        res = []
        for v in self.scope.all_vars():
            if v.ty.kind == 'array' and len(v.ty.dims) == ndims and (not writable or v.writable):
                if writable and not self.allow_gw and v.role == 'global':
                    continue
                if elem_keys is None or v.ty.elem.key in elem_keys:
                    res.append(v)
        return res

    def s_for(self, ind, d, arr=None):
        r = self.rng
        I = self.I
        lv = self.acquire_loop()
        self.use(lv)
        arrs = self.top_arrays(False, [k for k in NUMERIC + BITSTR + ('BOOL', 'STRING', 'TIME')])
        if arr is None and arrs and r.random() < 0.7:
            arr = r.choice(arrs)
        body = []
        if arr is not None:
            lo_t, lo, hi_t, hi = arr.ty.dims[0]
            if r.random() < 0.15 and hi > lo + 1:
                head = '%sFOR %s := %s TO %s BY -1 DO' % (ind, lv.name, hi_t, '%s+1' % lo_t if lo else '1')
                rng_ = (lo + 1, hi)
                shift = arr.writable and (self.allow_gw or arr.role != 'global')
            else:
                head = '%sFOR %s := %s TO %s DO' % (ind, lv.name, lo_t, hi_t)
                rng_ = (lo, hi)
                shift = False
            self.loops.append((lv.name, rng_[0], rng_[1]))
            self.loop_kinds.append('for')
            self.use(arr)
            ek = arr.ty.elem.key
            if shift:
                body.append('%s%s[%s] := %s[%s - 1];' % (ind + I, arr.name, lv.name, arr.name, lv.name))
            elif arr.writable and (self.allow_gw or arr.role != 'global') and r.random() < 0.5 \
                    and arr.ty.elem.kind in ('scalar', 'string'):
                body.append('%s%s[%s] := %s;' % (ind + I, arr.name, lv.name,
                                                 self.expr(ek, 0, True, arr.ty.elem.length, True)))
            else:
                acc = self.ref(ek, writable=True) if ek in NUMERIC else None
                if acc:
                    op = '+' if r.random() < 0.7 else '-'
                    body.append('%s%s := %s %s %s[%s];' % (ind + I, acc[0], acc[0], op, arr.name, lv.name))
                else:
                    body.append('%sIF %s[%s] %s THEN' % (ind + I, arr.name, lv.name,
                                                         self.cmp_tail(ek)))
                    body += self.block(1, ind + I + I, d + 2)
                    body.append(ind + I + self.end('END_IF'))
            body += self.block(r.randint(0, 2), ind + I, d + 1)
        else:
            lo = r.choice([0, 1])
            hi = lo + r.randint(2, 20)
            step = r.choice(['', '', '', ' BY 2'])
            head = '%sFOR %s := %d TO %d%s DO' % (ind, lv.name, lo, hi, step)
            self.loops.append((lv.name, lo, hi))
            self.loop_kinds.append('for')
            body += self.block(r.randint(1, 3), ind + I, d + 1)
        self.loops.pop()
        self.loop_kinds.pop()
        self.release_loop(lv)
        return [head] + body + [ind + self.end('END_FOR')]

    def cmp_tail(self, ek):
        if ek in NUMERIC or ek == 'TIME':
            return '%s %s' % (self.rng.choice(['>', '<', '>=']), self.expr(ek, 1, False, None, False))
        if ek == 'BOOL':
            return '= %s' % self.literal('BOOL')
        return '<> %s' % self.literal(ek, 8)

    def s_while(self, ind, d):
        r = self.rng
        I = self.I
        c = self.acquire_loop()
        self.use(c)
        n = r.randint(3, 12)
        out = ['%s%s := 0;' % (ind, c.name),
               '%sWHILE (%s < %d) AND (%s) DO' % (ind, c.name, n, self.cond())]
        self.loops.append((c.name, 0, n - 1))
        self.loop_kinds.append('while')
        out += self.block(r.randint(1, 3), ind + I, d + 1)
        out.append('%s%s := %s + 1;' % (ind + I, c.name, c.name))
        self.loops.pop()
        self.loop_kinds.pop()
        self.release_loop(c)
        return out + [ind + self.end('END_WHILE')]

    def s_repeat(self, ind, d):
        r = self.rng
        I = self.I
        c = self.acquire_loop()
        self.use(c)
        n = r.randint(2, 10)
        out = ['%s%s := 0;' % (ind, c.name), ind + 'REPEAT']
        self.loops.append((c.name, 0, n - 1))
        self.loop_kinds.append('repeat')
        out += self.block(r.randint(1, 3), ind + I, d + 1)
        out.append('%s%s := %s + 1;' % (ind + I, c.name, c.name))
        self.loops.pop()
        self.loop_kinds.pop()
        self.release_loop(c)
        return out + ['%sUNTIL (%s >= %d) OR (%s)' % (ind, c.name, n, self.cond()),
                      ind + self.end('END_REPEAT')]

    def s_exit(self, ind, d):
        return ['%sIF %s THEN' % (ind, self.cond()), ind + self.I + 'EXIT;', ind + self.end('END_IF')]

    def s_continue(self, ind, d):
        return ['%sIF %s THEN' % (ind, self.cond()), ind + self.I + 'CONTINUE;', ind + self.end('END_IF')]

    def fb_instances(self):
        return [v for v in self.scope.all_vars() if v.ty.kind == 'fb' and v.role == 'local']

    def s_fbcall(self, ind, d):
        v = self.rng.choice(self.fb_instances())
        return [ind + self.fb_call(v, v.name) + ';']

    def fb_call(self, v, inst_txt, must=()):
        r = self.rng
        fb = v.ty.fb
        self.use(v)
        args = []
        for n, t in fb.inputs + fb.inconst:
            if n in must or r.random() < 0.6:
                args.append('%s := %s' % (n, self.expr(t.key, 1, True, t.length, True)))
        for n, t in fb.inouts:
            b = v.bind[n]
            self.use(b)
            args.append('%s := %s' % (n, b.name))
        if not self.cs and fb.outputs and r.random() < 0.2:
            n, t = r.choice(fb.outputs)
            tg = self.ref(t.key, writable=True, simple=True)
            if tg:
                args.append('%s => %s' % (n, tg[0]))
        return '%s(%s)' % (inst_txt, ', '.join(args))

    def consume(self, key, text, ind, slen=None):
        """Store `text` (of type key) somewhere sensible."""
        t = self.ref(key, writable=True)
        if t is None:
            if key == 'BOOL':
                return ['%sIF %s THEN' % (ind, text)] + self.block(1, ind + self.I, 2) + [ind + self.end('END_IF')]
            ty = SCALAR.get(key) or (self.enum_by_key(key) if key.startswith('ENUM:') else string_ty(80))
            v = self.new_var(ty)
            self.use(v)
            return ['%s%s := %s;' % (ind, v.name, text)]
        return ['%s%s := %s;' % (ind, t[0], text)]

    # ------------------------------------------------------------------ features (FB / program parts)
    def std_instance(self, name):
        return self.new_var(self.std[name])

    def f_timer(self, ind):
        r = self.rng
        v = self.std_instance(r.choice(['TON', 'TON', 'TOF', 'TP']))
        pt = self.ref('TIME') if r.random() < 0.5 else None
        pt = pt[0] if pt else r.choice(TIME_LITS)
        self.use(v)
        out = ['%s%s(IN := %s, PT := %s);' % (ind, v.name, self.cond(), pt),
               '%sIF %s.Q THEN' % (ind, v.name)] + self.block(r.randint(1, 3), ind + self.I, 1)
        out.append(ind + self.end('END_IF'))
        if r.random() < 0.4:
            out += self.consume('TIME', v.name + '.ET', ind)
        return out

    def f_edge(self, ind):
        r = self.rng
        v = self.std_instance(r.choice(['R_TRIG', 'F_TRIG']))
        self.use(v)
        clk = self.ref('BOOL')
        out = ['%s%s(CLK := %s);' % (ind, v.name, clk[0] if clk else self.cond()),
               '%sIF %s.Q THEN' % (ind, v.name)]
        cnt = None
        for k in ('INT', 'DINT', 'UINT', 'UDINT'):
            cnt = self.ref(k, writable=True)
            if cnt:
                break
        if cnt:
            out.append('%s%s := %s + 1;' % (ind + self.I, cnt[0], cnt[0]))
        out += self.block(r.randint(0 if cnt else 1, 2), ind + self.I, 1)
        return out + [ind + self.end('END_IF')]

    def f_counter(self, ind):
        r = self.rng
        kind = r.choice(['CTU', 'CTU', 'CTD'])
        v = self.std_instance(kind)
        self.use(v)
        pv = self.ref('INT') if r.random() < 0.4 else None
        pv = pv[0] if pv else str(r.randint(2, 500))
        if kind == 'CTU':
            out = ['%s%s(CU := %s, RESET := %s, PV := %s);' % (ind, v.name, self.cond(), self.cond(), pv)]
        else:
            out = ['%s%s(CD := %s, LOAD := %s, PV := %s);' % (ind, v.name, self.cond(), self.cond(), pv)]
        out += self.consume('BOOL', v.name + '.Q', ind)
        out += self.consume('INT', v.name + '.CV', ind)
        return out

    def f_latch(self, ind):
        r = self.rng
        if r.random() < 0.5:
            v = self.std_instance('SR')
            out = ['%s%s(SET1 := %s, RESET := %s);' % (ind, v.name, self.cond(), self.cond())]
        else:
            v = self.std_instance('RS')
            out = ['%s%s(SET := %s, RESET1 := %s);' % (ind, v.name, self.cond(), self.cond())]
        self.use(v)
        return out + self.consume('BOOL', v.name + '.Q1', ind)

    def f_state(self, ind):
        r = self.rng
        I = self.I
        if not self.enums:
            return self.s_case(ind, 0)
        t = r.choice(self.enums)
        v = self.new_var(t, init=self.enum_lit(t, t.values[0][0]), word=r.choice(['State', 'Step', 'Mode', 'Phase']))
        self.use(v)
        out = [self.comment_line(ind), '%sCASE %s OF' % (ind, v.name)]
        for i, (vn, _) in enumerate(t.values):
            nxt = t.values[(i + 1) % len(t.values)][0]
            out.append('%s%s:' % (ind + I, self.enum_lit(t, vn)))
            out += self.block(r.randint(1, 2), ind + I + I, 2)
            out += ['%sIF %s THEN' % (ind + I + I, self.cond()),
                    '%s%s := %s;' % (ind + I + I + I, v.name, self.enum_lit(t, nxt)),
                    ind + I + I + self.end('END_IF')]
        if r.random() < 0.5:
            out += ['%sELSE' % (ind + I), '%s%s := %s;' % (ind + I + I, v.name, self.enum_lit(t, t.values[0][0]))]
        return out + [ind + self.end('END_CASE')]

    def pick_fb(self):
        fl = self.fbs
        return self.rng.choice(fl[-40:] if self.rng.random() < 0.7 else fl)

    def fb_instance(self, fbinfo):
        v = self.new_var(Ty('fb', fbinfo.name, fb=fbinfo), word=fbinfo.name[3:][:24])
        for n, t in fbinfo.inouts:
            b = self.new_var(t)
            v.bind[n] = b
        return v

    def f_subfb(self, ind):
        r = self.rng
        if not self.fbs:
            return self.f_timer(ind)
        fb = self.pick_fb()
        v = self.fb_instance(fb)
        out = [ind + self.fb_call(v, v.name) + ';']
        for n, t in r.sample(fb.outputs, min(len(fb.outputs), r.randint(1, 2))):
            if t.key == 'BOOL' and r.random() < 0.5:
                out += ['%sIF %s.%s THEN' % (ind, v.name, n)] + self.block(r.randint(1, 2), ind + self.I, 1) \
                    + [ind + self.end('END_IF')]
            else:
                out += self.consume(t.key, '%s.%s' % (v.name, n), ind, t.length)
        out += self.method_calls(v, ind)
        return out

    def method_calls(self, v, ind):
        return []

    def f_fbarray(self, ind):
        r = self.rng
        I = self.I
        kind = r.choice(['TON', 'TOF', 'R_TRIG'])
        c = r.choice(['MAX_ZONES', 'MAX_STATIONS', 'MAX_AXES'])
        self.use(next(v for v in self.root.vars if v.name == c))
        at = self.array_ty(self.std[kind], [('0', 0, '%s-1' % c, self.consts[c] - 1)])
        v = self.new_var(at)
        self.use(v)
        lv = self.acquire_loop()
        self.use(lv)
        self.loops.append((lv.name, 0, self.consts[c] - 1))
        self.loop_kinds.append('for')
        out = ['%sFOR %s := 0 TO %s - 1 DO' % (ind, lv.name, c)]
        if kind == 'R_TRIG':
            out.append('%s%s[%s](CLK := %s);' % (ind + I, v.name, lv.name, self.cond()))
        else:
            out.append('%s%s[%s](IN := %s, PT := %s);' % (ind + I, v.name, lv.name, self.cond(), r.choice(TIME_LITS)))
        out += ['%sIF %s[%s].Q THEN' % (ind + I, v.name, lv.name)] + self.block(r.randint(1, 2), ind + I + I, 2)
        out += [ind + I + self.end('END_IF'), ind + self.end('END_FOR')]
        self.loops.pop()
        self.loop_kinds.pop()
        self.release_loop(lv)
        return out

    def local_array(self, elem_keys):
        arrs = self.top_arrays(True, elem_keys)
        if arrs and self.rng.random() < 0.6:
            return self.rng.choice(arrs)
        k = self.rng.choice(elem_keys)
        ety = SCALAR[k] if k != 'STRING' else string_ty(self.rng.choice([16, 32]))
        c = self.rng.choice(['MAX_ITEMS', 'TABLE_LEN', 'HIST_LEN', 'MAX_STEPS'])
        return self.new_var(self.array_ty(ety, [('0', 0, '%s-1' % c, self.consts[c] - 1)]))

    def f_array(self, ind):
        r = self.rng
        I = self.I
        a = self.local_array(['INT', 'DINT', 'REAL', 'REAL', 'LREAL', 'UINT'])
        self.use(a)
        ek = a.ty.elem.key
        lo_t, lo, hi_t, hi = a.ty.dims[0]
        acc = self.ref(ek, writable=True)
        if acc is None:
            acc = (self.use(self.new_var(SCALAR[ek], word='Sum')), SCALAR[ek])
        mx = self.new_var(SCALAR[ek], word=r.choice(['Max', 'Peak', 'Top']))
        self.use(mx)
        lv = self.acquire_loop()
        self.use(lv)
        zero = '0.0' if ek in REALS else '0'
        out = [self.comment_line(ind),
               '%s%s := %s;' % (ind, acc[0], zero),
               '%s%s := %s[%s];' % (ind, mx.name, a.name, lo_t),
               '%sFOR %s := %s TO %s DO' % (ind, lv.name, lo_t, hi_t)]
        self.loops.append((lv.name, lo, hi))
        self.loop_kinds.append('for')
        out += ['%s%s := %s + %s[%s];' % (ind + I, acc[0], acc[0], a.name, lv.name),
                '%sIF %s[%s] > %s THEN' % (ind + I, a.name, lv.name, mx.name),
                '%s%s := %s[%s];' % (ind + I + I, mx.name, a.name, lv.name),
                ind + I + self.end('END_IF')]
        out += self.block(r.randint(0, 1), ind + I, 2)
        self.loops.pop()
        self.loop_kinds.pop()
        self.release_loop(lv)
        out.append(ind + self.end('END_FOR'))
        if a.writable and (self.allow_gw or a.role != 'global'):
            out += self.s_for(ind, 1, arr=a)
        return out

    def f_matrix(self, ind):
        vs = [v for v in self.top_arrays(True, list(NUMERIC), 2)]
        if not vs:
            return self.f_array(ind)
        a = self.rng.choice(vs)
        self.use(a)
        I = self.I
        li, lj = self.acquire_loop(), self.acquire_loop()
        self.use(li)
        self.use(lj)
        (l0, a0, h0, b0), (l1, a1, h1, b1) = a.ty.dims
        out = ['%sFOR %s := %s TO %s DO' % (ind, li.name, l0, h0),
               '%sFOR %s := %s TO %s DO' % (ind + I, lj.name, l1, h1)]
        self.loops += [(li.name, a0, b0), (lj.name, a1, b1)]
        self.loop_kinds += ['for', 'for']
        out.append('%s%s[%s, %s] := %s;' % (ind + I + I, a.name, li.name, lj.name,
                                            self.expr(a.ty.elem.key, 0, True, None, True)))
        out += self.block(self.rng.randint(0, 1), ind + I + I, 2)
        del self.loops[-2:]
        del self.loop_kinds[-2:]
        self.release_loop(li)
        self.release_loop(lj)
        return out + [ind + I + self.end('END_FOR'), ind + self.end('END_FOR')]

    def string_var(self):
        t = self.ref('STRING', writable=True) if self.rng.random() < 0.6 else None
        if t:
            return t
        v = self.new_var(string_ty(self.rng.choice([32, 40, 64, 80, 100, 128, 255])), word='Text')
        self.use(v)
        return v.name, v.ty

    def f_string(self, ind):
        r = self.rng
        I = self.I
        s, st = self.string_var()
        p = self.new_var(SCALAR['INT'], word='Pos')
        self.use(p)
        fn = {'INT': 'INT_TO_STRING', 'DINT': 'DINT_TO_STRING', 'REAL': 'REAL_TO_STRING'}
        k = r.choice(['INT', 'DINT', 'REAL'])
        num = self.expr(k, 1, False, None, True)
        out = [self.comment_line(ind),
               '%s%s := CONCAT(%s, %s(%s));' % (ind, s, self.literal('STRING', st.length), fn[k], num),
               '%s%s := FIND(%s, %s);' % (ind, p.name, s, self.literal('STRING', 4)),
               '%sIF %s > 0 THEN' % (ind, p.name),
               '%s%s := DELETE(%s, 1, %s);' % (ind + I, s, s, p.name),
               '%s%s := INSERT(%s, %s, %s);' % (ind + I, s, s, self.literal('STRING', 6), p.name),
               ind + self.end('END_IF')]
        if r.random() < 0.5:
            out.append('%s%s := REPLACE(%s, %s, 2, 1);' % (ind, s, s, self.literal('STRING', 4)))
        out += ['%sIF LEN(%s) > %d THEN' % (ind, s, r.randint(4, 30)),
                '%s%s := LEFT(%s, %d);' % (ind + I, s, s, r.randint(2, 20)),
                '%sELSE' % ind,
                '%s%s := CONCAT(%s, RIGHT(%s, %d));' % (ind + I, s, s, self.expr('STRING', 1), r.randint(1, 5)),
                ind + self.end('END_IF')]
        if r.random() < 0.5:
            out += self.consume('STRING', 'MID(%s, %d, %d)' % (s, r.randint(1, 8), r.randint(1, 4)), ind)
        return out

    def bit_var(self, key):
        t = self.ref(key, writable=True, simple=True)
        if t:
            return t[0]
        v = self.new_var(SCALAR[key], word=self.rng.choice(['Flags', 'Status', 'Bits', 'Mask']))
        self.use(v)
        return v.name

    def f_bits(self, ind):
        r = self.rng
        w = self.bit_var('WORD')
        dw = self.bit_var('DWORD')
        out = [self.comment_line(ind),
               '%s%s.%d := %s;' % (ind, w, r.randrange(16), self.cond()),
               '%s%s.%d := NOT %s.%d;' % (ind, w, r.randrange(16), w, r.randrange(16)),
               '%s%s := SHL(WORD_TO_DWORD(%s), %d) OR ROR(%s, %d);' % (ind, dw, w, r.randint(1, 15), dw, r.randint(1, 31)),
               '%s%s := (%s AND 16#%04X) XOR SHR(%s, %d);' % (ind, w, w, r.randrange(65536), w, r.randint(1, 8))]
        out += self.consume('BOOL', '%s.%d AND NOT %s.%d' % (dw, r.randrange(32), w, r.randrange(16)), ind)
        if r.random() < 0.5:
            by = self.bit_var('BYTE')
            out.append('%s%s := WORD_TO_BYTE(SHR(%s, 8)) OR ROL(%s, %d);' % (ind, by, w, by, r.randint(1, 7)))
        return out

    def f_search(self, ind):
        r = self.rng
        arrs = self.top_arrays(False, ['INT', 'DINT', 'UINT', 'STRING', 'BOOL', 'WORD'])
        if not arrs:
            return self.f_array(ind)
        a = r.choice(arrs)
        self.use(a)
        lo_t, lo, hi_t, hi = a.ty.dims[0]
        ek = a.ty.elem.key
        c = self.acquire_loop()
        self.use(c)
        tgt = self.expr(ek, 1, False, 8, False)
        out = ['%s%s := %s;' % (ind, c.name, lo_t)]
        if r.random() < 0.6:
            out.append('%sWHILE (%s < %s) AND (%s[%s] <> %s) DO' % (ind, c.name, hi_t, a.name, c.name, tgt))
            self.loops.append((c.name, lo, hi - 1))
            self.loop_kinds.append('while')
            out.append('%s%s := %s + 1;' % (ind + self.I, c.name, c.name))
            out.append(ind + self.end('END_WHILE'))
        else:
            self.loops.append((c.name, lo, hi - 1))
            self.loop_kinds.append('repeat')
            out += [ind + 'REPEAT', '%s%s := %s + 1;' % (ind + self.I, c.name, c.name),
                    '%sUNTIL (%s >= %s) OR (%s[%s] = %s)' % (ind, c.name, hi_t, a.name, c.name, tgt),
                    ind + self.end('END_REPEAT')]
        self.loops.pop()
        self.loop_kinds.pop()
        self.release_loop(c)
        out += self.consume('BOOL', '%s[%s] = %s' % (a.name, c.name, tgt), ind)
        return out

    def f_tablecall(self, ind):
        fl = [f for f in self.funcs if f.inouts]
        if not fl:
            return self.f_array(ind)
        f = self.rng.choice(fl[-30:])
        args = []
        for n, t in f.inputs + f.inconst:
            args.append((n, self.expr(t.key, 1, True, t.length, True)))
        for n, t in f.inouts:
            cand = [v for v in self.scope.all_vars() if v.ty.decl == t.decl and v.writable
                    and (self.allow_gw or v.role != 'global')]
            b = self.rng.choice(cand) if cand and self.rng.random() < 0.7 else self.new_var(t)
            self.use(b)
            args.append((n, b.name))
        return self.consume(f.ret.key, self.call_text(f.name, args), ind, f.ret.length)

    def f_random(self, ind):
        return self.block(self.rng.randint(2, 4), ind, 0)

    FEATURES = [('timer', 3), ('edge', 2), ('counter', 1.5), ('latch', 1), ('state', 2), ('subfb', 5),
                ('array', 2), ('matrix', 0.3), ('string', 1.5), ('bits', 1.5), ('search', 1),
                ('tablecall', 1), ('fbarray', 0.5), ('random', 2)]

    def features(self, k):
        fs = self.FEATURES
        return self.rng.choices([f for f, _ in fs], [w for _, w in fs], k=k)

    # ------------------------------------------------------------------ POU helpers
    def begin_body(self, scope, decl_scope=None, allow_gw=True):
        self.scope = scope
        self.decl_scope = decl_scope or scope
        self.loops, self.loop_kinds, self.loop_busy = [], [], []
        self.allow_gw = allow_gw

    def new_pou(self):
        self.pset = set()
        self.used_globals = []
        return Scope(self.root)

    def prune(self, scope, lines):
        """Drop locals (VAR) that the text never references."""
        ids = ident_set(lines)
        for v in list(scope.vars):
            if v.role == 'local' and v.name.lower() not in ids:
                scope.remove(v)

    def decl_line(self, v):
        init = ' := %s' % v.init if v.init is not None else ''
        com = ' (* %s *)' % v.comment if v.comment else ''
        return '%s : %s%s;%s' % (v.name, v.ty.decl, init, com)

    def decl_blocks(self, scope, ind=''):
        out = []
        groups = {}
        for v in scope.vars:
            groups.setdefault(v.role, []).append(v)
        done = set()
        for role, kw in self.ROLE_ORDER:
            if kw in done:
                continue
            vs = [v for rr, kk in self.ROLE_ORDER if kk == kw for v in groups.get(rr, [])]
            if not vs:
                continue
            done.add(kw)
            out.append(ind + kw)
            out += [ind + self.I + self.decl_line(v) for v in vs]
            out.append(ind + 'END_VAR')
        return out

    def maybe_comment(self):
        if self.rng.random() < 0.25:
            return self.rng.choice(self.comments)
        return None

    def add_inputs(self, sc, n, role='in', numeric_bias=False):
        out = []
        for _ in range(n):
            t = self.rand_scalar(numeric_bias, 80)
            v = self.new_var(t, role=role, comment=self.maybe_comment(), scope=sc)
            out.append((v.name, t))
        return out

    def register_function(self, info):
        self.funcs.append(info)
        if info.simple() and info.ret is not None:
            self.funcs_by_ret.setdefault(info.ret.key, []).append(info)

    # ------------------------------------------------------------------ FUNCTION
    def gen_function(self):
        r = self.rng
        I = self.BI
        name = self.pou_name('FC_')
        sc = self.new_pou()
        info = PouInfo('function', name)
        flav = r.choices(['calc', 'string', 'table', 'bits'], [6, 1.5, 1.2, 1])[0]
        self.begin_body(sc, allow_gw=False)
        if flav == 'calc':
            ret = self.rand_scalar(True, 80)
            if ret.key == 'STRING':
                ret = SCALAR['REAL']
            info.inputs = self.add_inputs(sc, r.randint(1, 4), numeric_bias=True)
        elif flav == 'string':
            ret = string_ty(r.choice([32, 40, 80, 128, 255]))
            st = string_ty(r.choice([20, 40, 80, 255]))
            v = self.new_var(st, role='in', word=r.choice(['Text', 'In', 'Name', 'Prefix']))
            info.inputs = [(v.name, st)] + self.add_inputs(sc, r.randint(1, 2), numeric_bias=True)
        elif flav == 'table':
            cands = [t for t in self.arrays if t.elem.kind == 'scalar' and t.elem.key in NUMERIC]
            if cands and r.random() < 0.5:
                at = r.choice(cands)
            else:
                c = r.choice(['MAX_ITEMS', 'TABLE_LEN', 'HIST_LEN'])
                at = self.array_ty(SCALAR[r.choice(['INT', 'REAL', 'DINT'])], [('0', 0, '%s-1' % c, self.consts[c] - 1)])
            ret = at.elem if r.random() < 0.6 else SCALAR['BOOL']
            info.inputs = self.add_inputs(sc, r.randint(0, 2), numeric_bias=True)
            a = self.new_var(at, role='inout', word=r.choice(['Data', 'Table', 'Values', 'Samples']))
            info.inouts = [(a.name, at)]
        else:
            ret = SCALAR[r.choice(['WORD', 'DWORD', 'BOOL', 'BYTE'])]
            info.inputs = [(self.new_var(SCALAR[k], role='in').name, SCALAR[k])
                           for k in r.sample(['WORD', 'DWORD', 'BYTE', 'INT', 'BOOL'], r.randint(1, 3))]
        if self.cs and r.random() < 0.3:
            t = SCALAR[r.choice(['REAL', 'INT', 'TIME', 'DINT'])]
            v = self.new_var(t, role='inconst', word=r.choice(['Factor', 'Limit', 'Offset', 'Gain']))
            info.inconst = [(v.name, t)]
        info.ret = ret
        for _ in range(r.randint(2, 5)):
            self.new_var(self.rand_scalar(True, 80), comment=self.maybe_comment(), scope=sc)
        body = []
        if flav == 'string':
            body += self.f_string(I)
        elif flav == 'table':
            body += self.f_array(I)
        elif flav == 'bits':
            body += self.f_bits(I)
        body += self.block(r.randint(2, 6), I, 0)
        self.use_inputs(sc, body, I)
        if r.random() < 0.2:
            body += ['%sIF %s THEN' % (I, self.cond()),
                     '%s%s := %s;' % (I + self.I, name, self.expr(ret.key, 0, True, ret.length)),
                     I + self.I + 'RETURN;', I + self.end('END_IF')]
        body += self.block(r.randint(0, 3), I, 0)
        body.append('%s%s := %s;' % (I, name, self.expr(ret.key, 0, True, ret.length)))
        self.prune(sc, body)
        self.register_function(info)
        self.stats['FUNCTION'] += 1
        return self.emit_pou('FUNCTION', name, ret, sc, body)

    def use_inputs(self, sc, body, ind):
        """Make sure every input is read at least once (realistic, keeps `unused` lint quiet)."""
        for v in sc.vars:
            if v.role in ('in', 'inconst') and not v.used and v.ty.kind in ('scalar', 'string', 'enum'):
                self.use(v)
                k = v.ty.key
                if k == 'BOOL':
                    body += ['%sIF %s THEN' % (ind, v.name)] + self.block(1, ind + self.I, 1) + [ind + self.end('END_IF')]
                else:
                    t = self.ref(k, writable=True)
                    if t:
                        body.append('%s%s := %s;' % (ind, t[0], v.name))
                    else:
                        body += ['%sIF %s %s THEN' % (ind, v.name, self.cmp_tail(k))] + \
                            self.block(1, ind + self.I, 1) + [ind + self.end('END_IF')]

    # ------------------------------------------------------------------ FUNCTION_BLOCK
    FB_INPUTS = [('BOOL', 'Enable'), ('BOOL', 'Execute'), ('BOOL', 'Reset'), ('BOOL', 'Auto')]
    FB_OUTPUTS = [('BOOL', 'Busy'), ('BOOL', 'Done'), ('BOOL', 'Error'), ('INT', 'ErrorId'),
                  ('REAL', 'Actual'), ('BOOL', 'Ready')]

    def fb_interface(self, sc, info):
        r = self.rng
        for k, w in r.sample(self.FB_INPUTS, r.randint(0, 2)):
            v = self.new_var(SCALAR[k], role='in', word=w, scope=sc)
            info.inputs.append((v.name, v.ty))
        info.inputs += self.add_inputs(sc, r.randint(1, 3))
        if self.cs and r.random() < 0.2:
            t = SCALAR[r.choice(['REAL', 'INT', 'TIME'])]
            v = self.new_var(t, role='inconst', word=r.choice(['MaxValue', 'Hysteresis', 'Timeout', 'Gain']), scope=sc)
            info.inconst.append((v.name, t))
        for k, w in r.sample(self.FB_OUTPUTS, r.randint(1, 3)):
            v = self.new_var(SCALAR[k], role='out', word=w, scope=sc)
            info.outputs.append((v.name, v.ty))
        for _ in range(r.randint(0, 2)):
            t = self.rand_scalar(False, 80)
            v = self.new_var(t, role='out', scope=sc)
            info.outputs.append((v.name, t))
        if r.random() < 0.18 and (self.structs or self.arrays):
            t = r.choice(self.structs + self.arrays)
            v = self.new_var(t, role='inout', word=r.choice(['Data', 'Cfg', 'Rec', 'Io']), scope=sc)
            info.inouts.append((v.name, t))
        for _ in range(r.randint(2, 5)):
            self.new_var(self.rand_scalar(), comment=self.maybe_comment(), scope=sc)
        if r.random() < 0.3 and self.structs:
            self.new_var(r.choice(self.structs), scope=sc)

    def gen_fb(self):
        r = self.rng
        I = self.BI
        name = self.pou_name('FB_')
        sc = self.new_pou()
        info = PouInfo('fb', name)
        self.fb_interface(sc, info)
        members = self.fb_members(sc, info)
        self.begin_body(sc)
        body = []
        feats = self.features(r.randint(2, 5))
        for f in feats:
            body += getattr(self, 'f_' + f)(I)
            if r.random() < 0.5:
                body += self.block(r.randint(1, 2), I, 0)
        body += self.member_calls(sc, info, I)
        self.use_inputs(sc, body, I)
        self.prune(sc, body + [l for m in members for l in m])
        self.fbs.append(info)
        self.stats['FUNCTION_BLOCK'] += 1
        return self.emit_pou('FUNCTION_BLOCK', name, None, sc, body, members)

    # methods (IEC) / actions (CODESYS) -- overridden by the CODESYS generator
    def fb_members(self, sc, info):
        r = self.rng
        I = self.I
        texts = []
        for _ in range(r.choices([0, 1, 2, 3], [1, 3, 3, 1.5])[0]):
            mname = self.uniq('M_' + self.words(r.choice([1, 2])), local=True)
            m = PouInfo('method', mname)
            m.owner = info
            ms = Scope(sc)
            if r.random() < 0.7:
                m.ret = self.rand_scalar(True, 80)
            for _ in range(r.randint(0, 3)):
                t = self.rand_scalar(True, 80)
                v = self.new_var(t, role='in', scope=ms)
                m.inputs.append((v.name, t))
            for _ in range(r.randint(0, 2)):
                self.new_var(self.rand_scalar(True, 80), scope=ms)
            self.begin_body(ms, ms)
            body = self.block(r.randint(2, 6), I + I, 0)
            if r.random() < 0.3:
                body = self.f_string(I + I) + body if r.random() < 0.5 else self.f_bits(I + I) + body
            self.use_inputs(ms, body, I + I)
            if m.ret is not None:
                body.append('%s%s := %s;' % (I + I, mname, self.expr(m.ret.key, 0, True, m.ret.length)))
            self.prune(ms, body)
            vis = r.choice(['PUBLIC', 'PUBLIC', 'PUBLIC', 'PRIVATE', 'PROTECTED', ''])
            m.vis = vis
            head = '%sMETHOD %s%s%s' % (I, vis + ' ' if vis else '', mname, ' : ' + m.ret.decl if m.ret else '')
            texts.append([head] + self.decl_blocks(ms, I) + body + [I + 'END_METHOD'])
            info.methods.append(m)
            self.stats['METHOD'] += 1
        # methods only appear after the body in the emitted text
        return texts

    def member_calls(self, sc, info, ind):
        out = []
        r = self.rng
        for m in info.methods:
            if r.random() < 0.75:
                args = [(n, self.expr(t.key, 1, True, t.length, True)) for n, t in m.inputs]
                callee = ('THIS^.' if r.random() < 0.3 else '') + m.name
                txt = self.call_text(callee, args) if args else callee + '()'
                if m.ret is None:
                    out.append('%s%s;' % (ind, txt))
                else:
                    out += self.consume(m.ret.key, txt, ind, m.ret.length)
        return out

    def method_calls(self, v, ind):
        out = []
        for m in v.ty.fb.methods:
            if m.vis == 'PUBLIC' and self.rng.random() < 0.6:
                args = [(n, self.expr(t.key, 1, True, t.length, True)) for n, t in m.inputs]
                txt = self.call_text('%s.%s' % (v.name, m.name), args) if args else '%s.%s()' % (v.name, m.name)
                if m.ret is None:
                    out.append('%s%s;' % (ind, txt))
                else:
                    out += self.consume(m.ret.key, txt, ind, m.ret.length)
        return out

    # ------------------------------------------------------------------ PROGRAM
    def gen_program(self, name=None):
        r = self.rng
        I = self.BI
        name = name or self.pou_name('PRG_')
        sc = self.new_pou()
        info = PouInfo('program', name)
        for _ in range(r.randint(3, 7)):
            self.new_var(self.rand_scalar(), comment=self.maybe_comment(), scope=sc)
        if self.structs:
            self.new_var(r.choice(self.structs), scope=sc)
        self.begin_body(sc)
        body = []
        feats = self.features(r.randint(3, 7))
        for f in feats:
            body += getattr(self, 'f_' + f)(I)
            if r.random() < 0.5:
                body += self.block(r.randint(1, 3), I, 0)
        self.prune(sc, body)
        self.programs.append(info)
        self.stats['PROGRAM'] += 1
        return self.emit_pou('PROGRAM', name, None, sc, body)

    def emit_pou(self, kind, name, ret, sc, body, members=()):
        out = ['// %s' % self.rng.choice(self.comments)] if self.rng.random() < 0.5 else []
        out.append('%s %s%s' % (kind, name, ' : ' + ret.decl if ret is not None else ''))
        if kind == 'PROGRAM' and not self.cs:
            ids = ident_set(body)
            for g in [g for g in self.root.vars if g.role == 'global' and g.name.lower() in ids]:
                sc.vars.append(Var(g.name, g.ty, 'external'))
        out += self.decl_blocks(sc)
        out += body
        for m in members:
            out += m
        out.append('END_' + kind)
        return out

    # ------------------------------------------------------------------ globals
    def gen_globals(self, n):
        r = self.rng
        vs = []
        for i in range(n):
            c = r.random()
            if c < 0.45:
                t = self.rand_scalar()
            elif c < 0.6 and self.structs:
                t = r.choice(self.structs)
            elif c < 0.7 and self.arrays:
                t = r.choice(self.arrays)
            elif c < 0.8 and self.structs:
                t = self.array_ty(r.choice(self.structs), [self.const_dim()])
            elif c < 0.86:
                a, b = r.sample(['MAX_AXES', 'MAX_ZONES', 'MAX_STATIONS'], 2)
                t = self.array_ty(SCALAR[r.choice(['REAL', 'INT', 'DINT'])],
                                  [('1', 1, a, self.consts[a]), ('0', 0, '%s-1' % b, self.consts[b] - 1)])
            elif c < 0.92 and self.enums:
                t = r.choice(self.enums)
            else:
                t = self.array_ty(self.rand_scalar(True, 40), [self.const_dim(r.choice([0, 1]))])
            name = self.uniq('g' + self.prefix(t) + self.words(r.choice([1, 2])))
            v = Var(name, t, 'global', comment=self.maybe_comment())
            if t.kind == 'scalar' and r.random() < 0.2:
                v.init = self.literal(t.key)
            elif t.kind == 'struct' and r.random() < 0.3:
                v.init = self.struct_init(t)
            elif (t.kind == 'array' and not self.cs and len(t.dims) == 1 and t.elem.kind == 'scalar'
                  and r.random() < 0.4):
                size = t.dims[0][3] - t.dims[0][1] + 1
                k = r.randint(1, 3)
                vals = [self.literal(t.elem.key) for _ in range(k)]
                if r.random() < 0.5:
                    vals.append('%d(%s)' % (size - k, self.literal(t.elem.key)))
                v.init = '[%s]' % ', '.join(vals)
            self.root.add(v)
            vs.append(v)
        return vs


# ----------------------------------------------------------------------------- IEC project
def generate(lines=30000, seed=DEFAULT_SEED):
    """Return {relative filename: content} for an IEC project of about `lines` lines."""
    g = Gen('iec', seed)
    r = g.rng
    I = g.I
    scale = max(1, lines // 3000)
    consts = g.gen_constants()
    tblocks = []
    for _ in range(3 + scale):
        tblocks.append(g.gen_enum())
    for i in range(4 + 2 * scale):
        tblocks.append(g.gen_struct())
        if i % 2:
            tblocks.append(g.gen_alias_array())
    gl = g.gen_globals(10 + 4 * scale)

    decl_lines = ['// Global constants and variables', 'VAR_GLOBAL CONSTANT']
    decl_lines += [I + g.decl_line(v) for v in consts] + ['END_VAR', '']
    chunk = max(1, len(gl) // 3)
    for i in range(0, len(gl), chunk):
        kw = 'VAR_GLOBAL' if i // chunk != 1 else 'VAR_GLOBAL RETAIN'
        decl_lines += [kw] + [I + g.decl_line(v) for v in gl[i:i + chunk]] + ['END_VAR', '']
    type_lines = ['// Data types']
    for t in tblocks:
        type_lines += g.type_text(t) + ['']

    pous = {k: [] for k in ('functions', 'fbs', 'programs')}
    order = ['functions', 'fbs', 'programs']
    total = len(type_lines) + len(decl_lines)
    cfg_reserve = 20 + len(g.programs)
    n = 0
    while total < lines - cfg_reserve - 40:
        n += 1
        if n <= 8:
            kind = 'functions'
        else:
            kind = r.choices(order, [4, 4, 1.3])[0]
        if kind == 'functions':
            txt = g.gen_function()
        elif kind == 'fbs':
            txt = g.gen_fb()
        else:
            txt = g.gen_program()
            cfg_reserve += 1
        pous[kind].append(txt + [''])
        total += len(txt) + 1
    # configuration with two tasks, every program instantiated
    cfg = ['CONFIGURATION Cfg_Main', I + 'RESOURCE Res_Main ON PLC',
           I + I + 'TASK TaskFast(INTERVAL := T#10ms, PRIORITY := 1);',
           I + I + 'TASK TaskSlow(INTERVAL := T#100ms, PRIORITY := 10);']
    for i, p in enumerate(g.programs):
        inst = g.uniq('inst' + p.name[4:])
        cfg.append('%sPROGRAM %s WITH %s : %s;' % (I + I, inst, 'TaskFast' if i % 3 == 0 else 'TaskSlow', p.name))
    cfg += [I + 'END_RESOURCE', 'END_CONFIGURATION']
    pous['programs'].append(cfg + [''])

    # split every kind into files of about equal size (~1000-2000 lines each)
    out = {'project.toml': '[project]\nname = "gen30k"\n',
           'src/types_gvl_01.st': '\n'.join(type_lines + [''] + decl_lines) + '\n'}
    for k in order:
        items = pous[k]
        size = sum(len(t) for t in items)
        nfiles = max(1, round(size / 1500.0))
        target = size / nfiles
        chunks, cur, acc = [], [], 0
        for t in items:
            if cur and acc + len(t) / 2.0 > target * (len(chunks) + 1) and len(chunks) < nfiles - 1:
                chunks.append(cur)
                cur = []
            cur += t
            acc += len(t)
        chunks.append(cur)
        for i, ls in enumerate(chunks):
            out['src/%s_%02d.st' % (k, i + 1)] = '\n'.join(ls) + '\n'
    generate.stats = dict(g.stats)
    return out


def write_files(outdir, files, encoding='utf-8', newline='\n'):
    for rel, content in files.items():
        p = os.path.join(outdir, rel)
        os.makedirs(os.path.dirname(p), exist_ok=True)
        with open(p, 'wb') as f:
            f.write(content.replace('\n', newline).encode(encoding))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('outdir')
    ap.add_argument('--lines', type=int, default=30000)
    ap.add_argument('--seed', type=int, default=DEFAULT_SEED)
    a = ap.parse_args(argv)
    files = generate(a.lines, a.seed)
    write_files(a.outdir, files)
    st = [c for f, c in files.items() if f.endswith('.st')]
    total = sum(c.count('\n') for c in st)
    s = generate.stats
    print('%d lines in %d .st files (%d FUNCTIONs, %d FUNCTION_BLOCKs, %d METHODs, %d PROGRAMs, %d TYPEs)'
          % (total, len(st), s['FUNCTION'], s['FUNCTION_BLOCK'], s['METHOD'], s['PROGRAM'], s['TYPE']))
    return 0


if __name__ == '__main__':
    sys.exit(main())
