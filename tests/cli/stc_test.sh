#!/usr/bin/env bash
# stc test (docs/projects.md, "Scenarios and golden traces") on the fixture
# tests/test-projects/axis_demo.  Usage: stc_test.sh STC FIXTURE CASE
set -u
STC=$(realpath "$1")
FIX=$2
CASE=$3
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
  # The golden trace is the CSV stc run --trace-out writes.
  "$STC" run "$FIX" --for 200ms --trace MAIN.state,Axis1.fSetPosition,MAIN.power.Status,GVL.sMode,MAIN.count \
    --trace-out "$TMP/run.csv" >"$TMP/out" 2>&1 || fail "stc run"
  cmp "$TMP/run.csv" "$FIX/expected/idle.csv" || fail "expected/idle.csv differs from stc run --trace-out"
  ;;

diff)
  # One constant changed: exit 1, the first differing cycle, variable, expected and actual.
  copy p
  sed -i 's/Acceleration := 100,/Acceleration := 200,/' "$TMP/p/src/Main.st"
  grep -q "Acceleration := 200" "$TMP/p/src/Main.st" || fail "fixture edit"
  run 1 "$TMP/p"
  has "FAIL p/move"
  has "first difference at cycle 102 (time T#101ms):"
  has "    Axis1.fSetPosition: expected 0.00005, actual 0.0001"
  has "PASS p/idle"
  lacks "MAIN.count: expected"
  has "passed, 1 failed"
  # REAL columns compare within the tolerance: a tiny change passes.
  copy q
  sed -i 's/^trace = .*/&\ntolerance = 1e-3/' "$TMP/q/scenarios/move.toml"
  sed -i 's/^0.5,E_State#Moving,\([0-9.]*\),/0.5,E_State#Moving,\1001,/' "$TMP/q/expected/move.csv"
  grep -q '^0.5,E_State#Moving,[0-9.]*001,' "$TMP/q/expected/move.csv" || fail "golden edit"
  run 0 "$TMP/q"
  sed -i 's/^tolerance = 1e-3/tolerance = 1e-12/' "$TMP/q/scenarios/move.toml"
  run 1 "$TMP/q"
  has "first difference at cycle 501 (time T#500ms):"
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

*)
  echo "unknown case $CASE"; exit 2 ;;
esac
echo "ok: $CASE"
