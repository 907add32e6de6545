#!/usr/bin/env bash
# stc test (docs/projects.md, "Scenarios and golden traces") on the fixture
# tests/test-projects/axis_demo.  Usage: stc_test.sh STC FIXTURE CASE
set -u
STC=$(realpath "$1")
FIX=$2
CASE=$3
FAULTS=$(dirname "$FIX")/fault_demo   # tests/test-projects/fault_demo
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

fail() { echo "FAILED: $*"; echo "--- output:"; cat "$TMP/out" 2>/dev/null; exit 1; }
# run EXPECTED_STATUS ARGS...: runs stc test, output in $TMP/out
run() {
  local want=$1; shift
  "$STC" test "$@" >"$TMP/out" 2>&1
  local rc=$?
  [ "$rc" = "$want" ] || fail "stc test $* exited $rc, expected $want"
}
has() { grep -qF -- "$1" "$TMP/out" || fail "output lacks: $1"; }
lacks() { ! grep -qF -- "$1" "$TMP/out" || fail "output has: $1"; }
copy() { cp -r "$FIX" "$TMP/$1"; }
# scenario PROJECT NAME TEXT: writes PROJECT/scenarios/NAME.toml
scenario() { mkdir -p "$TMP/$1/scenarios"; printf '%s\n' "$3" >"$TMP/$1/scenarios/$2.toml"; }

case $CASE in
pass)
  run 0 "$FIX"
  has "PASS axis_demo/drive_fault"
  has "PASS axis_demo/move"
  has "PASS axis_demo/types"
  has "4 passed, 0 failed"
  ;;

same-as-run)
  # The golden trace is the CSV stc run --trace-out writes, with REAL values rounded to the
  # tolerance: with tolerance = 0 byte for byte the same.
  copy p
  sed -i 's/^trace = .*/&\ntolerance = 0/' "$TMP/p/scenarios/idle.toml"
  run 0 "$TMP/p" --update --scenario idle
  "$STC" run "$FIX" --for 200ms --trace MAIN.state,Axis1.fSetPosition,MAIN.power.Status,GVL.sMode,MAIN.count \
    --trace-out "$TMP/run.csv" >"$TMP/out" 2>&1 || fail "stc run"
  cmp "$TMP/run.csv" "$TMP/p/expected/idle.csv" || fail "expected/idle.csv with tolerance 0 differs from stc run --trace-out"
  # With the default tolerance the header, times and non-REAL columns are the same.
  cut -d, -f1,2,4- "$TMP/run.csv" >"$TMP/run.cut"
  cut -d, -f1,2,4- "$FIX/expected/idle.csv" >"$TMP/golden.cut"
  cmp "$TMP/run.cut" "$TMP/golden.cut" || fail "expected/idle.csv differs from stc run --trace-out outside the REAL column"
  ;;

diff)
  # One constant changed: exit 1, each differing variable with its first and last
  # differing time and cycle, the number of rows, expected and actual.
  copy p
  sed -i 's/Acceleration := 100,/Acceleration := 200,/' "$TMP/p/src/Main.st"
  grep -q "Acceleration := 200" "$TMP/p/src/Main.st" || fail "fixture edit"
  run 1 "$TMP/p"
  has "FAIL p/move"
  has "  the trace differs from expected/move.csv in "
  has "    Axis1.fSetPosition: "
  has " rows differ, first at T#101ms (cycle 102): expected 0.00005, actual 0.0001; last at T#"
  has "    MAIN.move.Done: "
  has "PASS p/idle"
  lacks "MAIN.count: "
  has "passed, 1 failed"
  # REAL columns compare within the tolerance: a tiny change passes.
  copy q
  sed -i 's/^trace = .*/&\ntolerance = 1e-3/' "$TMP/q/scenarios/move.toml"
  sed -i 's/^0.5,E_State#Moving,\([0-9.]*\),/0.5,E_State#Moving,\1001,/' "$TMP/q/expected/move.csv"
  grep -q '^0.5,E_State#Moving,[0-9.]*001,' "$TMP/q/expected/move.csv" || fail "golden edit"
  run 0 "$TMP/q"
  sed -i 's/^tolerance = 1e-3/tolerance = 1e-9/' "$TMP/q/scenarios/move.toml"
  run 1 "$TMP/q"
  has "    Axis1.fSetPosition: 1 row differs, first at T#500ms (cycle 501): expected "
  # Bounded: at most 20 variables, then a count.
  mkdir -p "$TMP/w/src"
  echo '[project]' >"$TMP/w/project.toml"
  printf 'PROGRAM MAIN\nVAR a : ARRAY[0..24] OF DINT; i : INT; END_VAR\nFOR i := 0 TO 24 DO a[i] := a[i] + 1; END_FOR\nEND_PROGRAM\n' >"$TMP/w/src/Main.st"
  scenario w many "cycles = 10
trace = [$(for i in $(seq 0 24); do printf '"MAIN.a[%d]", ' "$i"; done)]"
  run 0 "$TMP/w" --update
  sed -i 's/a\[i\] + 1/a[i] + 2/' "$TMP/w/src/Main.st"
  run 1 "$TMP/w"
  has "  the trace differs from expected/many.csv in 10 of 10 rows, from T#0s (cycle 1) to T#9ms (cycle 10):"
  has "    MAIN.a[0]: 10 rows differ, first at T#0s (cycle 1): expected 1, actual 2; last at T#9ms (cycle 10)"
  has "    MAIN.a[19]: 10 rows differ"
  lacks "MAIN.a[20]: "
  has "    ... and 5 more variables differ"
  ;;

checks)
  # Each check kind, passing and failing, with the actual value.
  copy p
  rm -f "$TMP"/p/scenarios/*.toml
  scenario p ok '
duration = "1s"
[[set]]
at = "100ms"
var = "GVL.bStart"
value = "TRUE"
[[check]]
at = "999ms"
var = "MAIN.state"
equals = "E_State#Done"
[[check]]
var = "MAIN.move.Done"
rises_between = ["700ms", "900ms"]
[[check]]
var = "Axis1.fSetPosition"
min = 0
max = 10.0'
  scenario p bad '
duration = "1s"
[[set]]
at = "100ms"
var = "GVL.bStart"
value = "TRUE"
[[check]]
at = "500ms"
var = "MAIN.state"
equals = "E_State#Done"
[[check]]
at = "0.999s"
var = "Axis1.fSetPosition"
equals = 9.9
[[check]]
var = "MAIN.move.Done"
rises_between = ["100ms", "200ms"]
[[check]]
var = "MAIN.move.Error"
rises_between = ["0s", "1s"]
[[check]]
var = "Axis1.fSetPosition"
min = 1.0
[[check]]
var = "Axis1.fSetPosition"
max = 5.0
[[check]]
at = "2s"
var = "MAIN.count"
equals = 5'
  run 1 "$TMP/p"
  has "PASS p/ok"
  has "FAIL p/bad"
  has "check MAIN.state = E_State#Done at T#500ms (scenarios/bad.toml:7:1): actual E_State#Moving"
  has "check Axis1.fSetPosition = 9.9 at T#999ms (scenarios/bad.toml:11:1): actual 10.0"
  has "check MAIN.move.Done rises between T#100ms and T#200ms (scenarios/bad.toml:15:1): it first rises at T#"
  has "check MAIN.move.Error rises between T#0s and T#1s (scenarios/bad.toml:18:1): it never rises (FALSE at the end)"
  has "check Axis1.fSetPosition >= 1.0 (scenarios/bad.toml:21:1): actual minimum 0.0 at T#0s"
  has "check Axis1.fSetPosition <= 5.0 (scenarios/bad.toml:24:1): actual maximum 10.0 at T#"
  has "check MAIN.count = 5 at T#2s (scenarios/bad.toml:27:1): the run ends at T#1s, before that time"
  has "1 passed, 1 failed"
  ;;

update)
  copy p
  rm -rf "$TMP/p/expected"
  run 1 "$TMP/p"
  has "FAIL p/move"
  has "no expected/move.csv; run stc test --update"
  run 0 "$TMP/p" --update
  has "PASS p/move (" ; has "expected/move.csv written"
  cmp "$TMP/p/expected/move.csv" "$FIX/expected/move.csv" || fail "--update wrote a different move.csv"
  run 0 "$TMP/p"
  has "4 passed, 0 failed"
  # --update still evaluates the checks.
  sed -i 's/^equals = "E_State#Done"/equals = "E_State#Idle"/' "$TMP/p/scenarios/move.toml"
  run 1 "$TMP/p" --update
  has "FAIL p/move"
  has "actual E_State#Done"
  ;;

bad-scenario)
  copy p
  rm -f "$TMP"/p/scenarios/*.toml
  scenario p syntax 'duration = "1s"
trace = ["MAIN.state"
[[check]]'
  scenario p unknown_key 'duration = "1s"
trace = ["MAIN.state"]
[[check]]
at = "1s"
var = "MAIN.state"
equal = "Idle"'
  scenario p no_var 'cycles = 10
trace = ["MAIN.stat"]'
  scenario p bad_value 'cycles = 10
[[set]]
at = "1ms"
var = "MAIN.count"
value = "many"'
  scenario p bad_range 'cycles = 10
[[set]]
at = "1ms"
var = "GVL.nLevel"
value = "11"
[[check]]
at = "1ms"
var = "MAIN.state"
equals = "Running"'
  scenario p no_length 'trace = ["MAIN.state"]'
  scenario p no_axis 'cycles = 10
[[fault]]
at = "1ms"
axis = "Axis9"
kind = "drive_error"'
  # {attribute 'internal'} fields (the kernel handles) cannot be written or traced.
  scenario p internal_set 'cycles = 10
[[set]]
at = "1ms"
var = "MAIN.power.__handle"
value = "0"'
  scenario p internal_trace 'cycles = 10
trace = ["Axis1.__stcAxis"]'
  run 1 "$TMP/p"
  has "FAIL p/syntax"
  grep -qE "^  scenarios/syntax.toml:[0-9]+:[0-9]+: error: " "$TMP/out" || fail "no file:line:col for a TOML syntax error"
  has "FAIL p/unknown_key"
  has "scenarios/unknown_key.toml:6:1: error: unknown key 'equal' in [[check]]"
  has "FAIL p/no_var"
  has "error: trace MAIN.stat:"
  has "did you mean"
  has "FAIL p/bad_value"
  has "scenarios/bad_value.toml:2:1: error: MAIN.count: 'many' is not an integer literal"
  has "GVL.nLevel: '11' is not in the subrange 0..10"
  has "MAIN.state: 'Running' is not a value of E_State (E_State#Idle, E_State#Moving, E_State#Done, E_State#Failed)"
  has "FAIL p/no_length"
  has "scenarios/no_length.toml:1:1: error: the scenario needs exactly one of duration or cycles"
  has "FAIL p/no_axis"
  has "no [[axis]] named 'Axis9'"
  has "FAIL p/internal_set"
  has "'__handle' is internal to 'MC_Power'"
  has "FAIL p/internal_trace"
  has "'__stcAxis' is internal to 'AXIS_REF_SM3'"
  has "0 passed, 9 failed"
  # Not a project directory: exit 2.
  run 2 "$TMP/p/src"
  has "is not a project directory"
  run 2 "$TMP/nonexistent"
  # A project that does not compile fails every scenario.
  copy c
  echo "PROGRAM Broken x := ; END_PROGRAM" >"$TMP/c/src/Broken.st"
  run 1 "$TMP/c"
  has "the project does not compile"
  has "0 passed, 4 failed"
  ;;

parallel)
  # Two projects in parallel: output per project whole, in argument order,
  # the same every time (timings aside).
  copy a
  copy b
  sed -i 's/Acceleration := 100,/Acceleration := 200,/' "$TMP/b/src/Main.st"
  norm() { sed -E 's/\([0-9]+\.[0-9]+ s\)/(T)/' "$TMP/out"; }
  run 1 -j 2 "$TMP/b" "$TMP/a"
  norm >"$TMP/first"
  has "7 passed, 1 failed"
  for i in 1 2 3; do
    run 1 -j 2 "$TMP/b" "$TMP/a"
    norm >"$TMP/again"
    cmp "$TMP/first" "$TMP/again" || { diff "$TMP/first" "$TMP/again"; fail "parallel output differs between runs"; }
  done
  run 1 -j 1 "$TMP/b" "$TMP/a"
  norm >"$TMP/serial"
  cmp "$TMP/first" "$TMP/serial" || fail "-j 2 and -j 1 print differently"
  # b's report comes first, whole.
  awk '/^(PASS|FAIL) /{split($2, p, "/"); print p[1]}' "$TMP/first" | uniq >"$TMP/order"
  [ "$(cat "$TMP/order" | tr '\n' ' ')" = "b a " ] || fail "order: $(cat "$TMP/order")"
  ;;

empty)
  # A project without scenarios: nothing to run, success.
  mkdir -p "$TMP/e/src"
  echo '[project]' >"$TMP/e/project.toml"
  echo 'PROGRAM MAIN VAR x : INT; END_VAR x := x + 1; END_PROGRAM' >"$TMP/e/src/Main.st"
  run 0 "$TMP/e"
  has "0 passed, 0 failed"
  (cd "$TMP/e" && "$STC" test >"$TMP/out" 2>&1) || fail "stc test in the project directory"
  has "0 passed, 0 failed"
  ;;

fault)
  # tests/test-projects/fault_demo: the second of three scenarios divides by zero in its
  # slow task. That scenario FAILs with the fault at file:line:col; the others PASS.
  cp -r "$FAULTS" "$TMP/f"
  run 1 "$TMP/f"
  has "PASS f/a_first"
  has "FAIL f/b_divzero"
  has "f/src/Progs.st:11:23: error: runtime fault in task 'Slow', cycle 4 (T#30ms): division by zero [fault-division-by-zero]"
  has "    GVL.nQuotient := 1000 / GVL.nDivisor;"
  has "PASS f/c_third"
  has "2 passed, 1 failed"
  lacks "died"
  # The fault's scenario first, last, alone: the same verdicts.
  for only in b_divzero a_first; do
    run 1 "$TMP/f" --scenario b_divzero --scenario $only
    has "FAIL f/b_divzero"
    has "runtime fault in task 'Slow', cycle 4 (T#30ms): division by zero"
  done
  run 0 "$TMP/f" --scenario c_third --scenario a_first
  has "2 passed, 0 failed"
  ;;

scenario)
  # --scenario NAME: exact names, repeatable; an unknown one is exit 2 with a "did you mean".
  run 0 "$FIX" --scenario move --scenario idle
  has "PASS axis_demo/idle"
  has "PASS axis_demo/move"
  lacks "axis_demo/types"
  lacks "axis_demo/drive_fault"
  has "2 passed, 0 failed"
  run 2 "$FIX" --scenario mvoe
  has "stc: error: --scenario mvoe: no scenarios/mvoe.toml in '$FIX'; did you mean 'move'?"
  run 2 "$FIX" --scenario mov
  has "did you mean 'move'?"
  run 2 "$FIX" --scenario move.toml
  # With several projects, a name of any of them; the others run nothing.
  run 1 "$FIX" "$FAULTS" --scenario move --scenario b_divzero
  has "PASS axis_demo/move"
  has "FAIL fault_demo/b_divzero"
  has "1 passed, 1 failed"
  ;;

actual)
  # --actual DIR: the run's traces in DIR (created), the golden files untouched.
  copy p
  sed -i 's/Acceleration := 100,/Acceleration := 200,/' "$TMP/p/src/Main.st"
  cp -r "$TMP/p/expected" "$TMP/golden"
  run 1 "$TMP/p" --actual "$TMP/p/out/actual"
  has "FAIL p/move"
  has ", actual trace $TMP/p/out/actual/move.csv"
  for s in idle move types drive_fault; do
    [ -f "$TMP/p/out/actual/$s.csv" ] || fail "no actual $s.csv"
  done
  diff -r "$TMP/golden" "$TMP/p/expected" >/dev/null || fail "--actual changed the golden files"
  cmp -s "$TMP/p/out/actual/move.csv" "$TMP/p/expected/move.csv" && fail "the actual move.csv is the golden one"
  cmp "$TMP/p/out/actual/idle.csv" "$TMP/p/expected/idle.csv" || fail "the actual idle.csv (a passing scenario) differs"
  # The same traces again with --update: the actual trace is what --update writes.
  run 0 "$TMP/p" --update --scenario move
  cmp "$TMP/p/out/actual/move.csv" "$TMP/p/expected/move.csv" || fail "--actual differs from what --update writes"
  # Never expected/ or a directory in it (also through another spelling or a link).
  copy q
  run 2 "$TMP/q" --actual "$TMP/q/expected"
  has "where the golden files are; choose another directory"
  run 2 "$TMP/q" --actual "$TMP/q/src/../expected/sub"
  has "inside $TMP/q/expected"
  ln -s "$TMP/q/expected" "$TMP/link"
  run 2 "$TMP/q" --actual "$TMP/link"
  [ ! -e "$TMP/q/expected/sub" ] || fail "a directory was created in expected/"
  # A file in DIR that is a link out of it is refused, not followed.
  mkdir -p "$TMP/act"
  ln -s "$TMP/q/expected/move.csv" "$TMP/act/move.csv"
  cp "$TMP/q/expected/move.csv" "$TMP/move.before"
  sed -i 's/Acceleration := 100,/Acceleration := 200,/' "$TMP/q/src/Main.st"
  run 1 "$TMP/q" --actual "$TMP/act" --scenario move
  has "error: the actual trace move.csv not written to '$TMP/act'"
  cmp "$TMP/move.before" "$TMP/q/expected/move.csv" || fail "the golden file was written through a link"
  # A directory that cannot be created: exit 2.
  run 2 "$TMP/q" --actual "$TMP/move.before/sub"
  has "cannot create the directory"
  ;;

update-refused)
  # --update does not bless a failing scenario unless --force.
  copy p
  sed -i 's/Acceleration := 100,/Acceleration := 200,/' "$TMP/p/src/Main.st"
  sed -i 's/^equals = "E_State#Done"/equals = "E_State#Idle"/' "$TMP/p/scenarios/move.toml"
  cp "$TMP/p/expected/move.csv" "$TMP/move.before"
  run 1 "$TMP/p" --update
  has "FAIL p/move"
  has "actual E_State#Done"
  has "  expected/move.csv not written: 1 check fails (stc test --update --force writes it anyway)"
  has "PASS p/idle ("
  has "expected/idle.csv written"
  has "3 passed, 1 failed"
  cmp "$TMP/move.before" "$TMP/p/expected/move.csv" || fail "a failing scenario's golden file was written"
  run 1 "$TMP/p" --update --force
  has "FAIL p/move ("
  has "expected/move.csv written (--force)"
  cmp -s "$TMP/move.before" "$TMP/p/expected/move.csv" && fail "--force did not write the golden file"
  run 2 "$TMP/p" --force
  has "--force only goes with --update"
  # A faulting scenario: "it faults".
  cp -r "$FAULTS" "$TMP/f"
  cp "$TMP/f/expected/b_divzero.csv" "$TMP/b.before"
  echo "0,0,0,0" >>"$TMP/f/expected/b_divzero.csv"
  cp "$TMP/f/expected/b_divzero.csv" "$TMP/b.broken"
  run 1 "$TMP/f" --update
  has "expected/b_divzero.csv not written: it faults (stc test --update --force writes it anyway)"
  cmp "$TMP/b.broken" "$TMP/f/expected/b_divzero.csv" || fail "a faulting scenario's golden file was written"
  run 1 "$TMP/f" --update --force --scenario b_divzero
  cmp "$TMP/b.before" "$TMP/f/expected/b_divzero.csv" || fail "--force wrote another trace"
  ;;

sample)
  # sample = "100ms": rows at multiples of 100 ms; sample = "change": the first row, the
  # changes and the last row. --update writes them, the comparison reads them.
  copy p
  rm -rf "$TMP/p/expected"
  sed -i 's/^trace = .*/&\nsample = "100ms"/' "$TMP/p/scenarios/move.toml"
  scenario p steps '
duration = "1s"
trace = ["MAIN.state", "MAIN.move.Done"]
sample = "change"
[[set]]
at = "100ms"
var = "GVL.bStart"
value = "TRUE"'
  run 0 "$TMP/p" --update
  [ "$(cut -d, -f1 "$TMP/p/expected/move.csv" | tr '\n' ' ')" = "time 0 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9 " ] ||
    fail "move.csv rows: $(cut -d, -f1 "$TMP/p/expected/move.csv" | tr '\n' ' ')"
  # The start at 100 ms is seen in the same tick; Done at 0.8 s, the state a cycle later; the last tick.
  printf 'time,MAIN.state,MAIN.move.Done\n0,E_State#Idle,FALSE\n0.1,E_State#Moving,FALSE\n0.8,E_State#Moving,TRUE\n0.801,E_State#Done,TRUE\n0.999,E_State#Done,TRUE\n' >"$TMP/steps.want"
  cmp "$TMP/steps.want" "$TMP/p/expected/steps.csv" || fail "steps.csv: $(cat "$TMP/p/expected/steps.csv")"
  run 0 "$TMP/p"
  has "5 passed, 0 failed"
  # A later Done: the held values differ between the two edges.
  sed -i 's/Acceleration := 100,/Acceleration := 50,/' "$TMP/p/src/Main.st"
  run 1 "$TMP/p" --scenario steps
  has "MAIN.move.Done: "
  has "rows differ, first at T#"
  # Another sampling than the golden file's: the rows differ.
  copy q
  sed -i 's/^trace = .*/&\nsample = "2ms"/' "$TMP/q/scenarios/move.toml"
  run 1 "$TMP/q" --scenario move
  has "expected/move.csv has 1000 rows (last at T#999ms), this run 500 (last at T#998ms); 500 rows only in the golden file, the first at T#1ms"
  # Errors at the key: not a multiple of the base tick, above the duration, not a duration.
  copy r
  rm -f "$TMP"/r/scenarios/*.toml
  scenario r odd 'duration = "1s"
trace = ["MAIN.count"]
sample = "1.5ms"'
  scenario r long 'duration = "1s"
trace = ["MAIN.count"]
sample = "2s"'
  scenario r long_cycles 'cycles = 10
trace = ["MAIN.count"]
sample = "20ms"'
  scenario r typo 'duration = "1s"
trace = ["MAIN.count"]
sample = "chnage"'
  scenario r zero 'duration = "1s"
trace = ["MAIN.count"]
sample = "0ms"'
  scenario r notrace 'duration = "1s"
sample = "change"'
  run 1 "$TMP/r"
  has 'scenarios/odd.toml:3:10: error: sample = "1.5ms": not a multiple of the base cycle (T#1ms)'
  has "scenarios/long.toml:3:10: error: sample = \"2s\": above the scenario's duration (T#1s)"
  has "scenarios/long_cycles.toml:3:10: error: sample = \"20ms\": above the scenario's duration (10 cycles of T#1ms)"
  has 'scenarios/typo.toml:3:10: error: sample = "chnage": a duration (e.g. "10ms") or "change" is expected; did you mean "change"?'
  has 'scenarios/zero.toml:3:10: error: sample:'
  has 'scenarios/notrace.toml:2:10: error: sample = "change": the scenario has no trace to sample'
  has "0 passed, 6 failed"
  ;;

*)
  echo "unknown case $CASE"; exit 2 ;;
esac
echo "ok: $CASE"
