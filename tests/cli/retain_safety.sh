#!/usr/bin/env bash
# Retain that never destroys data (issue 14, item 5; docs/vm.md "Retain"):
# unreadable, foreign, newer and damaged files are never overwritten (exit 2, the file
# unchanged; --retain-reset replaces damaged/newer ones, never foreign ones); a changed
# layout restores what still matches, converts without loss and lists the rest as notes;
# restored values are checked against subranges, enums and string capacities; a save that
# fails is exit 4; symbolic links are written through (the link stays, the mode is kept).
set -euo pipefail
stc=$1
tmp=$(mktemp -d)
trap 'chmod -R u+rwx "$tmp" 2>/dev/null; rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }
# run EXPECTED-STATUS ARGS... : runs stc run -w, leaves stdout in $out and stderr in $err.
run() {
  local want=$1; shift
  set +e
  out=$("$stc" run -w "$@" 2>"$tmp/stderr"); rc=$?
  set -e
  err=$(cat "$tmp/stderr")
  [ "$rc" -eq "$want" ] || fail "stc run $*: exit $rc, expected $want; stderr: $err"
}
has() { grep -qF -- "$1" <<<"$err" || fail "stderr lacks '$1': $err"; }
# A retain file from Python: mk FILE VERSION 'path|signature|hexbytes'...
mk() {
  python3 - "$@" <<'PY'
import sys, struct, zlib
f, version, items = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
b = b'STCRET01' + struct.pack('<II', version, len(items))
for it in items:
    p, s, h = it.split('|')
    for x in (p.encode(), s.encode(), bytes.fromhex(h)):
        b += struct.pack('<I', len(x)) + x
open(f, 'wb').write(b + struct.pack('<I', zlib.crc32(b)))
PY
}

cat > a.st <<'ST'
TYPE E_Mode : (Idle, Run, Stop); END_TYPE
FUNCTION_BLOCK FB_Count
VAR n : DINT; old : INT := 3; END_VAR
n := n + 1;
END_FUNCTION_BLOCK
VAR_GLOBAL RETAIN
  r : DINT := 15;
  small : INT := 300;
  big : DINT := 100000;
  arr : ARRAY[1..5] OF INT := [1, 2, 3, 4, 5];
  gone : LREAL := 2.5;
  oldName : UDINT := 42;
  m : INT := 7;
  fb : FB_Count;
END_VAR
PROGRAM MAIN
fb();
END_PROGRAM
ST
cat > b.st <<'ST'
TYPE E_Mode : (Idle, Run, Stop); END_TYPE
FUNCTION_BLOCK FB_Count
VAR n : DINT; added : BOOL := TRUE; END_VAR
n := n + 1;
END_FUNCTION_BLOCK
VAR_GLOBAL RETAIN
  r : DINT(0..10) := 1;
  small : DINT;
  big : INT := 5;
  arr : ARRAY[1..3] OF DINT;
  newName : UDINT;
  m : E_Mode;
END_VAR
VAR_GLOBAL PERSISTENT
  fb : FB_Count;
END_VAR
PROGRAM MAIN
fb();
END_PROGRAM
ST

# (1) A changed layout: what matches is restored, the rest is listed.
run 0 a.st --cycles 3 --retain r.dat
run 0 b.st --cycles 1 --retain r.dat --watch r --watch small --watch big --watch arr --watch newName --watch m --watch fb.n --watch fb.added
[ "$out" = $'r = 1\nsmall = 300\nbig = 5\narr = [1, 2, 3]\nnewName = 0\nm = E_Mode#Idle\nfb.n = 4\nfb.added = TRUE' ] || fail "layout change: $out"
has "retained 'r' was not restored: 15 is outside DINT(0..10); it keeps its initial value"
has "retained 'small' changed type to DINT: converted from INT"
has "retained 'big' changed type from DINT to INT and cannot be converted without loss; it starts from its initial value"
has "retained 'arr' changed type to ARRAY[1..3] OF DINT: restored 3 of its 5 saved elements from ARRAY[1..5] OF INT"
has "retained 'm' was not restored: 7 is not a value of E_Mode; it keeps its initial value"
has "retained 'gone' (LREAL) is no longer declared; its saved value is dropped at the next save"
has "retained 'oldName' (UDINT) is no longer declared; its saved value is dropped at the next save (renamed to 'newName'?"
has "retained 'fb.old' (INT) is no longer declared"
has "retained 'fb.added' is not in the retain file; it starts from its initial value"

# (2) A string longer than its capacity, a BOOL that is not 0/1, an enum out of range:
#     not restored, the initial value kept (file forged: the program never writes these).
cat > s.st <<'ST'
TYPE E_Mode : (Idle, Run, Stop); END_TYPE
VAR_GLOBAL RETAIN
  s : STRING(80) := 'init';
  w : WSTRING(4) := "ab";
  w2 : WSTRING(10);
  ok : BOOL := TRUE;
  modes : ARRAY[0..2] OF E_Mode;
  x : DINT;
END_VAR
PROGRAM MAIN
x := x + 1;
END_PROGRAM
ST
mk long.dat 2 "s|STRING(80) RETAIN|$(printf '61%.0s' $(seq 81))" "w|WSTRING(4) RETAIN|41004200430044004500" \
   "w2|WSTRING(4) RETAIN|41004200430044004500" \
   "ok|BOOL RETAIN|07" "modes|ARRAY[0..2] OF INT RETAIN|010009000200" "x|DINT RETAIN|05000000"
run 0 s.st --cycles 1 --retain long.dat --watch s --watch w --watch w2 --watch ok --watch modes --watch x
[ "$out" = $'s = \'init\'\nw = "ab"\nw2 = ""\nok = TRUE\nmodes = [E_Mode#Run, E_Mode#Idle, E_Mode#Stop]\nx = 6' ] || fail "value checks: $out"
has "retained 's' was not restored: its length exceeds the capacity of STRING(80); it keeps its initial value"
has "retained 'w' was not restored: its length exceeds the capacity of WSTRING(4)"
has "retained 'w2' changed type from WSTRING(4) to WSTRING(10) and cannot be converted"   # (a damaged old value)
has "retained 'ok' was not restored: the byte 7 is not a BOOL"
has "retained 'modes[1]' was not restored: 9 is not a value of E_Mode"

# (3) A file written before issue 14 (format 1: whole variables) is still read.
cat > v1.st <<'ST'
TYPE T_Pair : STRUCT a : DINT; b : DINT; END_STRUCT END_TYPE
VAR_GLOBAL RETAIN
  x : DINT;
  pr : T_Pair;
END_VAR
PROGRAM MAIN
x := x + 1;
END_PROGRAM
ST
mk v1.dat 1 "x|DINT RETAIN|29000000" "pr|T_Pair{8:a@0=DINT;b@4=DINT;} RETAIN|0700000008000000"
run 0 v1.st --cycles 1 --retain v1.dat --watch x --watch pr.a --watch pr.b
[ "$out" = $'x = 42\npr.a = 7\npr.b = 8' ] || fail "format 1: $out"
[ "$(head -c 9 v1.dat | tail -c 1 | od -An -tu1 | tr -d ' ')" = 2 ] || fail "format 1 file not rewritten as format 2"

# (4) Files that are not ours: exit 2, nothing runs, the file is unchanged.
cp a.st foreign.st
run 2 b.st --cycles 1 --retain foreign.st
has "'foreign.st' is not a retain file"; has "left as it is and nothing ran"
cmp -s a.st foreign.st || fail "a foreign file was changed"
run 2 b.st --cycles 1 --retain foreign.st --retain-reset       # never, not even with --retain-reset
cmp -s a.st foreign.st || fail "--retain-reset changed a foreign file"
mkdir adir
run 2 b.st --cycles 1 --retain adir
has "'adir' is a directory, not a file"
if [ "$(id -u)" != 0 ]; then   # (root reads everything)
  cp r.dat locked.dat; chmod 000 locked.dat
  run 2 b.st --cycles 1 --retain locked.dat
  has "cannot open 'locked.dat'"
  chmod 600 locked.dat; cmp -s r.dat locked.dat || fail "an unreadable file was changed"
fi
# Newer formats and damaged files: exit 2; --retain-reset starts cold and replaces them.
mk newer.dat 3
cp newer.dat newer.orig
run 2 b.st --cycles 1 --retain newer.dat
has "format version 3, newer than this stc reads (1 to 2)"
cmp -s newer.dat newer.orig || fail "a newer file was changed"
printf 'STCRET07xxxxxxxx' > newer7.dat
run 2 b.st --cycles 1 --retain newer7.dat
has "has the format STCRET07, newer than this stc reads"
cp r.dat damaged.dat
printf '\xff' | dd of=damaged.dat bs=1 seek=30 conv=notrunc status=none
cp damaged.dat damaged.orig
run 2 b.st --cycles 1 --retain damaged.dat
has "'damaged.dat' is damaged (bad checksum)"; has "--retain-reset starts from the initial values and replaces it"
cmp -s damaged.dat damaged.orig || fail "a damaged file was changed"
run 0 b.st --cycles 2 --retain damaged.dat --retain-reset --watch fb.n
[ "$out" = "fb.n = 2" ] || fail "--retain-reset: $out"
has "--retain-reset: cold start, the file is replaced at the first save"
run 0 b.st --cycles 1 --retain damaged.dat --watch fb.n
[ "$out" = "fb.n = 3" ] || fail "after --retain-reset: $out"
run 2 b.st --cycles 1 --retain-reset
has "--retain-reset needs --retain FILE"

# (5) Saves that cannot succeed: found before the run (exit 2) or reported (exit 4).
run 2 b.st --cycles 1 --retain "$tmp/no/such/dir/r.dat"
has "cannot be saved"; has "nothing ran"
printf 'not ours' > blocked.dat.tmp
run 4 b.st --cycles 1 --retain blocked.dat --watch fb.n
[ "$out" = "fb.n = 1" ] || fail "exit 4 still prints the watches: $out"
has "cannot save retain file: 'blocked.dat.tmp' is in the way"
[ "$(cat blocked.dat.tmp)" = "not ours" ] || fail "a foreign .tmp was overwritten"
# A file put in the retain file's place during the run is not overwritten by the last save.
cat > slow.st <<'ST'
VAR_GLOBAL RETAIN n : DINT; END_VAR
PROGRAM MAIN
n := n + 1;
END_PROGRAM
ST
"$stc" run slow.st --for 1h --realtime --retain swapped.dat >/dev/null 2>"$tmp/swap.err" &
pid=$!
sleep 1
echo "user data" > swapped.dat
kill -TERM "$pid"
set +e; wait "$pid"; rc=$?; set -e
[ "$rc" -eq 4 ] || fail "a swapped-in file: exit $rc, expected 4: $(cat "$tmp/swap.err")"
grep -qF "is no longer a retain file" "$tmp/swap.err" || fail "no message for a swapped-in file: $(cat "$tmp/swap.err")"
[ "$(cat swapped.dat)" = "user data" ] || fail "a file swapped in during the run was overwritten"
if [ "$(id -u)" != 0 ]; then
  mkdir ro; run 0 b.st --cycles 1 --retain ro/r.dat
  chmod 500 ro
  run 2 b.st --cycles 1 --retain ro/r.dat
  chmod 700 ro
fi

# (6) Symbolic links: written through (atomically, next to the target), the link stays,
#     the target's permissions are kept; a dangling link creates its target.
mkdir store
ln -s store/plc.dat link.dat
run 0 b.st --cycles 2 --retain link.dat
[ -L link.dat ] && [ -f store/plc.dat ] || fail "the link was replaced or the target not created"
chmod 600 store/plc.dat
run 0 b.st --cycles 1 --retain link.dat --watch fb.n
[ "$out" = "fb.n = 3" ] || fail "through the link: $out"
[ -L link.dat ] || fail "the link was replaced by a file"
[ "$(stat -c %a store/plc.dat)" = 600 ] || fail "mode not kept: $(stat -c %a store/plc.dat)"
[ ! -e store/plc.dat.tmp ] && [ ! -e link.dat.tmp ] || fail "a temporary file was left"
echo "retain safety: ok"
