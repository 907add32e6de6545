#!/usr/bin/env python3
"""Generate a realistic CODESYS V2.3 library export (one LIBRARY.EXP file) for stress tests.

    gen_codesys23_export.py OUTDIR [--pous N] [--seed S]

Writes OUTDIR/project.toml ([build] dialect = "codesys") and OUTDIR/src/LIBRARY.EXP:
one Latin-1 encoded, CRLF file in the CODESYS 2.3 export style -- every object starts with
the comment pragmas (* @NESTEDCOMMENTS := 'Yes' *), (* @PATH := '\\/...' *),
(* @OBJECTFLAGS := '0, 8' *), (* @SYMFILEFLAGS := '2048' *), POUs separate declaration and
body with (* @END_DECLARATION := '0' *), actions follow END_FUNCTION_BLOCK at top level,
global variable lists end with @OBJECT_END / @CONNECTIONS comments.  Objects come in the
order a 2.3 export writes them: POUs, then data types, then global variable lists.

N (default 600) is the number of POUs (FUNCTIONs, FUNCTION_BLOCKs, PROGRAMs incl. PLC_PRG).
The code uses POINTER TO (ADR, p^, pointer arithmetic, DWORD addresses), STRING(n) of many
sizes, VAR_INPUT CONSTANT, VAR_IN_OUT, arrays bounded by global constants, all statement
kinds, the string functions, standard FBs, conversions, bit access, shifts/rotates,
MIN/MAX/LIMIT/SEL/MUX and ABS/SQRT/SIN/COS.  Calls only reach POUs generated earlier (no
recursion), every call uses existing parameters of matching types, every FUNCTION assigns
its result and locals that end up unreferenced are not declared.  Deterministic for a seed.
"""
import argparse
import os
import sys

sys.dont_write_bytecode = True          # do not leave __pycache__ in tools/
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gen_project as gp               # noqa: E402  (shared generator core)

SEED = 2300

TEXTS_LATIN1 = ['Start', 'Stop', 'Störung', 'Übertemperatur', 'Füllstand', 'Motor läuft', 'Temp °C',
                'µs', 'Tür offen', 'Drehzahl', 'Ölstand niedrig', 'Größe', 'OK', 'Fehler: ', 'Achse ',
                'Schritt ', 'bereit', 'Druck bar', ' / ', 'Wärme', 'Zähler', 'Not-Aus', 'Quittieren',
                'Ventil zu', 'Ventil auf', 'Pumpe', 'Grenzwert °C', 'Zeit µs', 'Lüfter', 'Kühlung',
                'Zeile$N', 'Tab$T', 'Sollwert', 'Istwert', 'Schütz', 'Endlage']
COMMENTS_LATIN1 = ['Zustandsmaschine für die Achse', 'Temperatur in °C', 'Zeitbasis in µs',
                   'Überwachung Türschalter', 'Größe des Puffers prüfen', 'Störmeldung quittieren',
                   'Füllstand prüfen', 'Sollwert für Drehzahl', 'Wärmetauscher / Ölkühler',
                   'Rückmeldung abwarten', 'Zähler für Gutteile', 'Grenzwerte prüfen',
                   'Bits in Statuswort packen', 'Analogwert filtern', 'Tabelle durchsuchen',
                   'nur im Automatikbetrieb', 'Rampe für Sollwert (* alt: 10 s *)',
                   'Zeiger über den Puffer schieben', 'Prüfsumme über Speicherbereich',
                   'TODO: Verstärkung vor Ort einstellen', 'letzten gültigen Wert merken',
                   'Druck in bar, Auflösung 0,01', 'Geschwindigkeit in mm/s (* nicht µm/s *)']
PATHS = {
    'FUNCTION': ['\\/Utils\\/Math', '\\/Utils\\/String', '\\/Utils\\/Bits', '\\/Utils\\/Memory',
                 '\\/Utils\\/Convert', '\\/Process\\/Calc'],
    'FUNCTION_BLOCK': ['\\/Motion\\/Axis', '\\/Motion\\/Drive', '\\/Process\\/Valves',
                       '\\/Process\\/Pumps', '\\/Process\\/Temperature', '\\/Handling\\/Conveyor',
                       '\\/Handling\\/Gripper', '\\/Alarm', '\\/Communication'],
    'PROGRAM': ['\\/Main', '\\/Main\\/Stations', '\\/Service'],
    'TYPE': ['\\/Types', '\\/Types\\/Motion', '\\/Types\\/Process', ''],
}


class Codesys23Gen(gp.Gen):
    FEATURES = gp.Gen.FEATURES + [('pointer', 1.5), ('ptrstruct', 1.2), ('dwaddr', 0.7),
                                  ('ptrcall', 1.2), ('ptrarray', 0.5)]

    def __init__(self, seed=SEED):
        super().__init__('codesys', seed)
        self.texts = TEXTS_LATIN1
        self.comments = COMMENTS_LATIN1
        self.conv['DINT'].append(('TIME_TO_DINT', 'TIME'))
        self.conv['TIME'].append(('DINT_TO_TIME', 'DINT'))
        self.conv['STRING'] += [('BOOL_TO_STRING', 'BOOL'), ('TIME_TO_STRING', 'TIME')]
        self.conv['DWORD'].append(('TIME_TO_DWORD', 'TIME'))
        self.conv['UDINT'].append(('BYTE_TO_UDINT', 'BYTE'))
        self.ptr_funcs = []      # (PouInfo, flavour)
        self.objects = []        # finished text objects (lists of lines)

    # ------------------------------------------------------------------ export framing
    def header(self, kind, extra=()):
        return ["(* @NESTEDCOMMENTS := 'Yes' *)"] + list(extra) + [
            "(* @PATH := '%s' *)" % self.rng.choice(PATHS[kind]),
            "(* @OBJECTFLAGS := '0, 8' *)",
            "(* @SYMFILEFLAGS := '2048' *)"]

    def type_text(self, t):
        I = self.I
        out = self.header('TYPE')
        if t.kind == 'enum':
            out += ['TYPE %s :' % t.name, '(']
            out += ['%s%s := %d%s' % (I, n, v, ',' if i < len(t.values) - 1 else '')
                    for i, (n, v) in enumerate(t.values)]
            out += [');', 'END_TYPE']
        elif t.kind == 'struct':
            out += ['TYPE %s :' % t.name, 'STRUCT']
            for mn, mt in t.members:
                init = ' := %s' % t.inits[mn] if mn in t.inits else ''
                com = ' (* %s *)' % self.rng.choice(self.comments) if self.rng.random() < 0.2 else ''
                out.append('%s%s : %s%s;%s' % (I, mn, mt.decl, init, com))
            out += ['END_STRUCT', 'END_TYPE']
        else:
            out += ['TYPE %s : %s;' % (t.decl, t.alias_of), 'END_TYPE']
        return out + ['']

    def global_list(self, listname, kw, vs):
        out = ["(* @NESTEDCOMMENTS := 'Yes' *)", "(* @GLOBAL_VARIABLE_LIST := '%s' *)" % listname,
               "(* @PATH := '' *)", "(* @OBJECTFLAGS := '0, 8' *)", "(* @SYMFILEFLAGS := '2048' *)",
               kw]
        out += [self.I + self.decl_line(v) for v in vs]
        out += ['END_VAR', '', "(* @OBJECT_END := '%s' *)" % listname,
                '(* @CONNECTIONS := %s' % listname, "FILENAME : ''", 'FILETIME : 0', 'EXPORT : 0',
                'NUMOFCONNECTIONS : 0', '*)', '']
        return out

    def emit_pou(self, kind, name, ret, sc, body, members=()):
        out = self.header(kind)
        out.append('%s %s%s' % (kind, name, ' : ' + ret.decl if ret is not None else ''))
        if self.rng.random() < 0.4:
            out.append('(* %s *)' % self.rng.choice(self.comments))
        out += self.decl_blocks(sc)
        out.append("(* @END_DECLARATION := '0' *)")
        out += body
        out.append('END_' + kind)
        for m in members:
            out += m
        return out + ['', '']

    # ------------------------------------------------------------------ actions instead of methods
    def fb_members(self, sc, info):
        r = self.rng
        texts = []
        for _ in range(r.choices([0, 1, 2, 3], [2, 3, 2, 1])[0]):
            aname = self.uniq('A_' + self.words(1), local=True)
            self.begin_body(sc)
            body = []
            if r.random() < 0.4:
                body += getattr(self, 'f_' + r.choice(['bits', 'string', 'array', 'search', 'pointer']))('')
            body += self.block(r.randint(2, 5), '', 0)
            info.actions.append(aname)
            self.stats['ACTION'] += 1
            texts.append(['ACTION\t%s:' % aname] + body + ['END_ACTION', ''])
        return texts

    def member_calls(self, sc, info, ind):
        out = []
        for a in info.actions:
            c = self.rng.random()
            if c < 0.4:
                out.append('%s%s();' % (ind, a))
            elif c < 0.8:
                out += ['%sIF %s THEN' % (ind, self.cond()), '%s%s();' % (ind + self.I, a), ind + 'END_IF']
        return out

    def method_calls(self, v, ind):
        out = []
        for a in v.ty.fb.actions:
            if self.rng.random() < 0.2:
                out.append('%s%s.%s();' % (ind, v.name, a))
        return out

    # ------------------------------------------------------------------ pointer features
    def byte_buffer(self, min_len=8):
        arrs = [v for v in self.top_arrays(True, ['BYTE']) if v.ty.dims[0][3] - v.ty.dims[0][1] >= min_len]
        if arrs and self.rng.random() < 0.5:
            return self.rng.choice(arrs)
        c = self.rng.choice(['BUF_SIZE', 'TABLE_LEN', 'BUF_SIZE'])
        return self.new_var(self.array_ty(gp.SCALAR['BYTE'], [('0', 0, '%s-1' % c, self.consts[c] - 1)]),
                            word=self.rng.choice(['Buf', 'Data', 'Frame', 'Rx', 'Tx']))

    def ptr_var(self, target, word=None):
        return self.new_var(gp.Ty('ptr', None, 'POINTER TO ' + target.decl, target=target), word=word)

    def loop_over(self, lv, dims):
        lo_t, lo, hi_t, hi = dims
        self.loops.append((lv.name, lo, hi))
        self.loop_kinds.append('for')

    def end_loop(self, lv):
        self.loops.pop()
        self.loop_kinds.pop()
        self.release_loop(lv)

    def f_pointer(self, ind):
        """Walk a byte buffer with a POINTER TO BYTE (p^, p := p + 1)."""
        r = self.rng
        I = self.I
        buf = self.byte_buffer()
        p = self.ptr_var(gp.SCALAR['BYTE'], word=r.choice(['Byte', 'Cur', 'Src', 'Dst']))
        lv = self.acquire_loop()
        for v in (buf, p, lv):
            self.use(v)
        lo_t, lo, hi_t, hi = buf.ty.dims[0]
        start = 'ADR(%s)' % buf.name if r.random() < 0.5 else 'ADR(%s[%s])' % (buf.name, lo_t)
        out = ['%s(* %s *)' % (ind, r.choice(self.comments)),
               '%s%s := %s;' % (ind, p.name, start),
               '%sFOR %s := %s TO %s DO' % (ind, lv.name, lo_t, hi_t)]
        self.loop_over(lv, buf.ty.dims[0])
        c = r.random()
        if c < 0.4:
            out.append('%s%s^ := INT_TO_BYTE(%s);' % (ind + I, p.name, lv.name))
        elif c < 0.7:
            out.append('%s%s^ := %s^ XOR %s;' % (ind + I, p.name, p.name, self.expr('BYTE', 1, False, None, False)))
        else:
            out += self.consume('BYTE', '%s^' % p.name, ind + I)
        out.append('%s%s := %s + 1;' % (ind + I, p.name, p.name))
        self.end_loop(lv)
        out.append(ind + 'END_FOR')
        if r.random() < 0.4:
            # pointer to a scalar
            k = r.choice(['INT', 'REAL', 'DINT', 'WORD'])
            t = self.ref(k, writable=True, simple=True)
            if t:
                q = self.ptr_var(gp.SCALAR[k])
                self.use(q)
                out += ['%s%s := ADR(%s);' % (ind, q.name, t[0]),
                        '%s%s^ := %s;' % (ind, q.name, self.expr(k, 1, False, None, True))]
                out += self.consume(k, '%s^' % q.name, ind)
        return out

    def struct_array(self):
        arrs = [v for v in self.top_arrays(True, None) if v.ty.elem.kind == 'struct'
                and any(mt.kind in ('scalar', 'string') for _, mt in v.ty.elem.members)]
        if arrs and self.rng.random() < 0.6:
            return self.rng.choice(arrs)
        sts = [t for t in self.structs if any(mt.kind in ('scalar', 'string') for _, mt in t.members)]
        c = self.rng.choice(['MAX_ITEMS', 'MAX_AXES', 'MAX_ZONES'])
        return self.new_var(self.array_ty(self.rng.choice(sts), [('0', 0, '%s-1' % c, self.consts[c] - 1)]))

    def f_ptrstruct(self, ind):
        """Walk an array of structs: p := p + SIZEOF(a[0])."""
        r = self.rng
        I = self.I
        a = self.struct_array()
        st = a.ty.elem
        p = self.ptr_var(st, word=st.name[3:])
        lv = self.acquire_loop()
        for v in (a, p, lv):
            self.use(v)
        lo_t, lo, hi_t, hi = a.ty.dims[0]
        mems = [(mn, mt) for mn, mt in st.members if mt.kind in ('scalar', 'string')]
        out = ['%s%s := ADR(%s[%s]);' % (ind, p.name, a.name, lo_t),
               '%sFOR %s := %s TO %s DO' % (ind, lv.name, lo_t, hi_t)]
        self.loop_over(lv, a.ty.dims[0])
        for mn, mt in r.sample(mems, min(len(mems), r.randint(1, 2))):
            if r.random() < 0.5:
                out.append('%s%s^.%s := %s;' % (ind + I, p.name, mn, self.expr(mt.key, 1, True, mt.length, True)))
            else:
                out += self.consume(mt.key, '%s^.%s' % (p.name, mn), ind + I, mt.length)
        size = 'SIZEOF(%s[%s])' % (a.name, lo_t) if r.random() < 0.5 else 'SIZEOF(%s^)' % p.name
        out.append('%s%s := %s + %s;' % (ind + I, p.name, p.name, size))
        self.end_loop(lv)
        return out + [ind + 'END_FOR']

    def f_dwaddr(self, ind):
        """Addresses held in a DWORD, as 2.3 libraries do (dw := ADR(buf); p := dw)."""
        r = self.rng
        buf = self.byte_buffer(8)
        dw = self.new_var(gp.SCALAR['DWORD'], word='Addr')
        p = self.ptr_var(gp.SCALAR['BYTE'])
        for v in (buf, dw, p):
            self.use(v)
        off = r.randint(1, 7)
        out = ['%s%s := ADR(%s);' % (ind, dw.name, buf.name),
               '%s%s := %s + %d;' % (ind, dw.name, dw.name, off),
               '%s%s := %s;' % (ind, p.name, dw.name)]
        out += self.consume('BYTE', '%s^' % p.name, ind)
        if r.random() < 0.5:
            out.append('%s%s^ := %s;' % (ind, p.name, self.expr('BYTE', 1, False, None, True)))
        return out

    def f_ptrarray(self, ind):
        """POINTER TO ARRAY: pa^[i]."""
        r = self.rng
        I = self.I
        arrs = [v for v in self.top_arrays(True, ['INT', 'REAL', 'DINT', 'WORD'])]
        if not arrs:
            return self.f_pointer(ind)
        a = r.choice(arrs)
        p = self.ptr_var(a.ty, word=r.choice(['Table', 'Data', 'Values']))
        lv = self.acquire_loop()
        for v in (a, p, lv):
            self.use(v)
        lo_t, lo, hi_t, hi = a.ty.dims[0]
        ek = a.ty.elem.key
        out = ['%s%s := ADR(%s);' % (ind, p.name, a.name),
               '%sFOR %s := %s TO %s DO' % (ind, lv.name, lo_t, hi_t)]
        self.loop_over(lv, a.ty.dims[0])
        out.append('%s%s^[%s] := %s;' % (ind + I, p.name, lv.name, self.expr(ek, 1, False, None, True)))
        self.end_loop(lv)
        return out + [ind + 'END_FOR']

    def struct_var(self, st):
        cand = [v for v in self.scope.all_vars() if v.ty is st and v.writable
                and (self.allow_gw or v.role != 'global')]
        if cand and self.rng.random() < 0.6:
            return self.rng.choice(cand)
        return self.new_var(st)

    def f_ptrcall(self, ind):
        """Call a function taking POINTER TO parameters: FC(ADR(buf), SIZEOF(buf))."""
        r = self.rng
        if not self.ptr_funcs:
            return self.f_pointer(ind)
        f, flav = r.choice(self.ptr_funcs[-30:])
        args = []
        for n, t in f.params():
            if t.kind == 'ptr' and t.target.key == 'BYTE':
                buf = self.byte_buffer()
                self.use(buf)
                args.append(buf.name if r.random() < 0.1 else 'ADR(%s)' % buf.name)
                last_buf = buf
            elif t.kind == 'ptr':
                sv = self.struct_var(t.target)
                self.use(sv)
                args.append('ADR(%s)' % sv.name)
            elif n.lower().startswith('udilen'):
                args.append('SIZEOF(%s)' % last_buf.name)
            else:
                args.append(self.expr(t.key, 1, True, t.length, True))
        return self.consume(f.ret.key, '%s(%s)' % (f.name, ', '.join(args)), ind, f.ret.length)

    # ------------------------------------------------------------------ pointer functions
    def gen_ptr_function(self):
        r = self.rng
        I = self.I
        B = self.BI
        flav = r.choice(['crc', 'sum', 'xor', 'count', 'struct', 'struct'])
        if flav == 'struct' and not self.structs:
            flav = 'crc'
        name = self.pou_name('FC_' + {'crc': 'Crc', 'sum': 'Sum', 'xor': 'Xor', 'count': 'Count',
                                       'struct': 'Get'}[flav])
        sc = self.new_pou()
        info = gp.PouInfo('function', name)
        self.begin_body(sc, allow_gw=False)
        body = []
        if flav != 'struct':
            pd = self.new_var(gp.Ty('ptr', None, 'POINTER TO BYTE', target=gp.SCALAR['BYTE']), role='in',
                              word='Data', comment=r.choice(self.comments) if r.random() < 0.3 else None)
            pl = gp.Var(self.uniq('udiLen', local=True), gp.SCALAR['UDINT'], 'in')
            sc.add(pl)
            info.inputs = [(pd.name, pd.ty), (pl.name, pl.ty)]
            cur = self.ptr_var(gp.SCALAR['BYTE'], word='Cur')
            idx = self.new_var(gp.SCALAR['DINT'], word='Idx')
            for v in (pd, pl, cur, idx):
                self.use(v)
            body.append('%s%s := %s;' % (B, cur.name, pd.name))
            if flav == 'crc':
                ret = gp.SCALAR['WORD']
                acc = self.new_var(ret, word='Crc')
                lv = self.acquire_loop()
                self.use(acc)
                self.use(lv)
                poly = r.choice(['16#A001', '16#8408', '16#1021'])
                body += ['%s%s := 16#FFFF;' % (B, acc.name),
                         '%sFOR %s := 1 TO UDINT_TO_DINT(%s) DO' % (B, idx.name, pl.name),
                         '%s%s := %s XOR BYTE_TO_WORD(%s^);' % (B + I, acc.name, acc.name, cur.name),
                         '%sFOR %s := 0 TO 7 DO' % (B + I, lv.name),
                         '%sIF %s.0 THEN' % (B + I * 2, acc.name),
                         '%s%s := SHR(%s, 1) XOR %s;' % (B + I * 3, acc.name, acc.name, poly),
                         '%sELSE' % (B + I * 2),
                         '%s%s := SHR(%s, 1);' % (B + I * 3, acc.name, acc.name),
                         '%sEND_IF' % (B + I * 2), '%sEND_FOR' % (B + I),
                         '%s%s := %s + 1;' % (B + I, cur.name, cur.name), '%sEND_FOR' % B]
                self.release_loop(lv)
            elif flav in ('sum', 'count'):
                ret = gp.SCALAR['UDINT']
                acc = self.new_var(ret, word='Result')
                self.use(acc)
                body += ['%s%s := 0;' % (B, acc.name), '%s%s := 0;' % (B, idx.name),
                         '%sWHILE DINT_TO_UDINT(%s) < %s DO' % (B, idx.name, pl.name)]
                if flav == 'sum':
                    body.append('%s%s := %s + BYTE_TO_UDINT(%s^);' % (B + I, acc.name, acc.name, cur.name))
                else:
                    pat = gp.Var(self.uniq('byPattern', local=True), gp.SCALAR['BYTE'], 'in')
                    sc.vars.insert(2, pat)
                    sc.dirty = True
                    info.inputs.insert(2, (pat.name, pat.ty))
                    self.use(pat)
                    body += ['%sIF %s^ = %s THEN' % (B + I, cur.name, pat.name),
                             '%s%s := %s + 1;' % (B + I * 2, acc.name, acc.name), '%sEND_IF' % (B + I)]
                body += ['%s%s := %s + 1;' % (B + I, cur.name, cur.name),
                         '%s%s := %s + 1;' % (B + I, idx.name, idx.name), '%sEND_WHILE' % B]
            else:
                ret = gp.SCALAR['BYTE']
                acc = self.new_var(ret, word='Chk')
                self.use(acc)
                body += ['%s%s := 0;' % (B, acc.name),
                         '%sFOR %s := 1 TO UDINT_TO_DINT(%s) DO' % (B, idx.name, pl.name),
                         '%s%s := %s XOR %s^;' % (B + I, acc.name, acc.name, cur.name),
                         '%s%s := %s + 1;' % (B + I, cur.name, cur.name), '%sEND_FOR' % B]
            body.append('%s%s := %s;' % (B, name, acc.name))
        else:
            sts = [t for t in self.structs if any(mt.kind == 'scalar' for _, mt in t.members)]
            st = r.choice(sts)
            mems = [(mn, mt) for mn, mt in st.members if mt.kind == 'scalar']
            mn, ret = r.choice(mems)
            pd = self.new_var(gp.Ty('ptr', None, 'POINTER TO ' + st.name, target=st), role='in', word=st.name[3:])
            self.use(pd)
            info.inputs = [(pd.name, pd.ty)]
            info.inputs += self.add_inputs(sc, r.randint(0, 2), numeric_bias=True)
            body += ['%sIF %s <> 0 THEN' % (B, pd.name),
                     '%s%s := %s^.%s;' % (B + I, name, pd.name, mn)]
            others = [(n2, t2) for n2, t2 in st.members if t2.kind in ('scalar', 'string') and n2 != mn]
            if others and r.random() < 0.6:
                n2, t2 = r.choice(others)
                body.append('%s%s^.%s := %s;' % (B + I, pd.name, n2, self.expr(t2.key, 1, True, t2.length, True)))
            body += ['%sELSE' % B, '%s%s := %s;' % (B + I, name, self.literal(ret.key)), '%sEND_IF' % B]
            self.use_inputs(sc, body, B)
        info.ret = ret
        self.prune(sc, body)
        self.funcs.append(info)
        self.ptr_funcs.append((info, flav))
        self.stats['FUNCTION'] += 1
        return self.emit_pou('FUNCTION', name, ret, sc, body)

    # ------------------------------------------------------------------ PLC_PRG
    def gen_plc_prg(self):
        I = self.I
        sc = self.new_pou()
        self.begin_body(sc)
        cyc = self.new_var(gp.SCALAR['UDINT'], word='Cycle')
        self.use(cyc)
        body = ['%s := %s + 1;' % (cyc.name, cyc.name)]
        for i, p in enumerate(self.programs):
            if i % 7 == 3:
                body += ['IF %s MOD 2 = 0 THEN' % cyc.name, I + '%s();' % p.name, 'END_IF']
            else:
                body.append('%s();' % p.name)
        self.stats['PROGRAM'] += 1
        return self.emit_pou('PROGRAM', 'PLC_PRG', None, sc, body)


def generate(pous=600, seed=SEED):
    """Return (files, stats); files maps relative names to str contents (LF line ends)."""
    g = Codesys23Gen(seed)
    r = g.rng
    scale = max(1, pous // 60)
    consts = g.gen_constants()
    types = []
    for _ in range(3 + scale):
        types.append(g.gen_enum())
    for i in range(5 + 2 * scale):
        types.append(g.gen_struct())
        if i % 2:
            types.append(g.gen_alias_array())
    gl = g.gen_globals(12 + 4 * scale)

    pou_objs = []
    n = 0
    while n < pous - 1:
        n += 1
        if n <= 6:
            kind = 'fn'
        elif n <= 10:
            kind = 'ptrfn'
        else:
            kind = r.choices(['fn', 'ptrfn', 'fb', 'prg'], [3.2, 0.8, 4.5, 1.5])[0]
        if kind == 'fn':
            pou_objs.append(g.gen_function())
        elif kind == 'ptrfn':
            pou_objs.append(g.gen_ptr_function())
        elif kind == 'fb':
            pou_objs.append(g.gen_fb())
        else:
            pou_objs.append(g.gen_program())
    pou_objs.append(g.gen_plc_prg())

    lines = []
    for o in pou_objs:
        lines += o
    for t in types:
        lines += g.type_text(t)
    lines += g.global_list('Konstanten', 'VAR_GLOBAL CONSTANT', consts)
    third = max(1, len(gl) // 3)
    lines += g.global_list('Globale_Variablen', 'VAR_GLOBAL', gl[:2 * third])
    lines += g.global_list('Retain_Variablen', 'VAR_GLOBAL RETAIN', gl[2 * third:])
    files = {'project.toml': '[project]\nname = "codesys23_stress"\n[build]\ndialect = "codesys"\n',
             'src/LIBRARY.EXP': '\n'.join(lines) + '\n'}
    stats = dict(g.stats)
    stats['POU'] = len(pou_objs)
    return files, stats


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('outdir')
    ap.add_argument('--pous', type=int, default=600)
    ap.add_argument('--seed', type=int, default=SEED)
    a = ap.parse_args(argv)
    files, st = generate(a.pous, a.seed)
    p = os.path.join(a.outdir, 'project.toml')
    os.makedirs(os.path.join(a.outdir, 'src'), exist_ok=True)
    with open(p, 'w', newline='\n') as f:
        f.write(files['project.toml'])
    exp = files['src/LIBRARY.EXP']
    with open(os.path.join(a.outdir, 'src', 'LIBRARY.EXP'), 'wb') as f:
        f.write(exp.replace('\n', '\r\n').encode('latin-1'))
    print('%d lines, %d POUs (%d FUNCTIONs, %d FUNCTION_BLOCKs, %d PROGRAMs), %d ACTIONs, %d TYPEs'
          % (exp.count('\n'), st['POU'], st['FUNCTION'], st['FUNCTION_BLOCK'], st['PROGRAM'],
             st['ACTION'], st['TYPE']))
    return 0


if __name__ == '__main__':
    sys.exit(main())
