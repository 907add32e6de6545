#!/usr/bin/env bash
# Hostile project.toml, scenario and command-line inputs (issue 14, item 4):
# each must end in a clear error with its exit status (1 input, 2 command
# line) and message, never a signal, an abort, a hang or silent acceptance.
# Usage: config_errors.sh STC GROUP   (GROUP: schema durations tasks files checks axes)
set -u
STC=$1 GROUP=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
failures=0

# expect NAME CODE REGEX -- COMMAND...: runs COMMAND (at most 20 s) and checks both.
expect() {
  local name=$1 code=$2 pattern=$3
  shift 4
  local out rc
  out=$(timeout 20 "$@" 2>&1); rc=$?
  if [ "$rc" -ne "$code" ]; then
    echo "FAILED $name: exit status $rc, expected $code"; echo "$out" | tail -8; failures=$((failures + 1)); return
  fi
  if ! grep -Eq -- "$pattern" <<<"$out"; then
    echo "FAILED $name: output does not match /$pattern/:"; echo "$out" | tail -8; failures=$((failures + 1)); return
  fi
  echo "ok $name"
}

# A fresh project in $TMP/$1: a counter program, a REAL, a scenario; project.toml from stdin.
project() {
  local d=$TMP/$1
  rm -rf "$d"
  mkdir -p "$d/src" "$d/scenarios"
  cat >"$d/project.toml"
  cat >"$d/src/Main.st" <<'EOF'
VAR_GLOBAL
  r : REAL := 1.5;
  go : BOOL;
END_VAR
PROGRAM MAIN
VAR n : INT; END_VAR
n := n + 1;
END_PROGRAM
EOF
  cat >"$d/scenarios/run.toml" <<'EOF'
duration = "10ms"
[[check]]
at = "10ms"
var = "MAIN.n"
equals = "10"
EOF
}
# A scenario $2 (stdin) in project $1.
scenario() { cat >"$TMP/$1/scenarios/$2.toml"; }

case $GROUP in
schema)
  project ok <<<'[project]
name = "ok"'
  expect valid-project 0 "1 passed, 0 failed" -- "$STC" test "$TMP/ok"
  project typo <<'EOF'
[project]
name = "typo"
libraries = ["codesys_sm3"]
[[axis]]
name = "Axis1"
max_velocty = 5.0
EOF
  expect axis-key-typo 1 "typo/project.toml:6:1: error: unknown key 'max_velocty' in \[\[axis\]\]; did you mean 'max_velocity'\?" -- "$STC" check "$TMP/typo"
  expect axis-key-typo-caret 1 "max_velocty = 5.0" -- "$STC" check "$TMP/typo"
  project table <<<'[projet]
name = "x"'
  expect table-typo 1 "project.toml:1:2: error: unknown key 'projet' in project.toml; did you mean 'project'\?" -- "$STC" check "$TMP/table"
  project build <<<'[build]
dialekt = "iec"'
  expect build-key-typo 1 "did you mean 'dialect'\?" -- "$STC" check "$TMP/build"
  project choice <<<'[build]
dialect = "codesis"'
  expect choice-typo 1 "project.toml:2:11: error: \[build\] dialect = \"codesis\": must be \"codesys\" or \"iec\"; did you mean \"codesys\"\?" -- "$STC" check "$TMP/choice"
  project type <<<'[build]
dialect = 3'
  expect wrong-type 1 "\[build\] dialect = 3: a string is expected" -- "$STC" check "$TMP/type"
  project unknown <<<'colour = "red"'
  expect unknown-no-hint 1 "unknown key 'colour' in project.toml \(known keys: project, build, task, axis, group, io, cam, cnc_program\)" -- "$STC" check "$TMP/unknown"
  project libs <<<'[project]
libraries = ["codesys_sm"]'
  expect library-typo 1 "unknown library 'codesys_sm'.*did you mean 'codesys_sm3'\?" -- "$STC" check "$TMP/libs"
  project io <<'EOF'
[[io]]
var = "go"
kind = "delay"
source = "go"
delay = "5ms"
dealy = "1ms"
EOF
  expect io-key-typo 1 "unknown key 'dealy' in \[\[io\]\]; did you mean 'delay'\?" -- "$STC" check "$TMP/io"
  project scen <<<''
  scenario scen run <<<'durration = "1s"'
  expect scenario-key-typo 1 "scenarios/run.toml:1:1: error: unknown key 'durration' in the scenario; did you mean 'duration'\?" -- "$STC" test "$TMP/scen"
  scenario scen run <<'EOF'
duration = "10ms"
[[check]]
at = "5ms"
var = "MAIN.n"
equal = "3"
EOF
  expect check-key-typo 1 "scenarios/run.toml:5:1: error: unknown key 'equal' in \[\[check\]\]; did you mean 'equals'\?" -- "$STC" test "$TMP/scen"
  scenario scen run <<<'cycles = 5
duration = "5ms"'
  expect duration-and-cycles 1 "the scenario needs exactly one of duration or cycles" -- "$STC" test "$TMP/scen"
  scenario scen run <<<'description = "no length"'
  expect no-length 1 "the scenario needs exactly one of duration or cycles" -- "$STC" test "$TMP/scen"
  scenario scen run <<<'duration = "5ms"
trace = ["MAIN.n; x"]'
  expect trace-not-a-variable 1 "trace = .*a variable name is expected" -- "$STC" test "$TMP/scen"
  ;;
durations)
  project d <<<''
  for bad in ".s" "1.2.3s" "" "-1s" "99999999999999h" "1s2h" "5" "10 parsecs" "1.5s3ms" "T#" "$(printf '9%.0s' $(seq 5000))ms" "1e3ms"; do
    expect "for-'${bad:0:20}'" 2 "stc: error: --for: .*\(e\.g\. 10s" -- "$STC" run "$TMP/d" --for "$bad"
  done
  expect for-overflow-message 2 "out of range" -- "$STC" run "$TMP/d" --for 99999999999999h
  expect for-empty-message 2 "an empty duration" -- "$STC" run "$TMP/d" --for ""
  expect for-dots-message 2 "one decimal point at most" -- "$STC" run "$TMP/d" --for 1.2.3s
  expect for-dot-s-message 2 "a digit is expected before '\.'" -- "$STC" run "$TMP/d" --for .s
  expect interval-zero 2 "--interval: 'T#0s' is not positive" -- "$STC" run "$TMP/d" --interval T#0s --cycles 1
  expect watchdog-negative 2 "--watchdog: '-5ms' is negative" -- "$STC" run "$TMP/d" --watchdog -5ms --cycles 1
  expect for-1h30m 0 "MAIN.n = 5400" -- "$STC" run "$TMP/d" --for 1h30m --interval 1s --watch MAIN.n
  expect for-T#-prefix 0 "MAIN.n = 10" -- "$STC" run "$TMP/d" --for T#10ms --watch MAIN.n
  expect for-fraction 0 "MAIN.n = 1500" -- "$STC" run "$TMP/d" --for 1.5s --watch MAIN.n
  expect for-underscores 0 "MAIN.n = 1000" -- "$STC" run "$TMP/d" --for 1_000ms --watch MAIN.n
  scenario d run <<<'duration = "10ms"
[[set]]
at = "99999999999999h"
var = "go"
value = true'
  expect scenario-at-overflow 1 "scenarios/run.toml:3:6: error: \[\[set\]\] at: '99999999999999h' is out of range" -- "$STC" test "$TMP/d"
  scenario d run <<<'duration = ".s"'
  expect scenario-duration-dot-s 1 "scenarios/run.toml:1:12: error: duration: '\.s': a digit is expected before '\.'" -- "$STC" test "$TMP/d"
  scenario d run <<<"duration = \"$(printf '1%.0s' $(seq 5000))s\""
  expect scenario-5000-digits 1 "scenarios/run.toml:1:12: error: duration: '1111.*' is out of range" -- "$STC" test "$TMP/d"
  scenario d run <<<'duration = "0s"'
  expect scenario-duration-zero 1 "duration: 'T?#?0s' is not positive" -- "$STC" test "$TMP/d"
  project io <<<"[[io]]
var = \"go\"
kind = \"delay\"
source = \"go\"
delay = \"$(printf '7%.0s' $(seq 5000))ms\""
  expect toml-5000-digits 1 "project.toml:5:9: error: \[\[io\]\] delay: '7777.*' is out of range" -- "$STC" check "$TMP/io"
  project fault <<<'[project]
libraries = ["codesys_sm3"]
[[axis]]
name = "Ax"
[[axis.fault]]
at = "1.2.3s"
kind = "drive_error"'
  expect axis-fault-at 1 "project.toml:6:6: error: \[\[axis.fault\]\] at: '1\.2\.3s': a number has one decimal point at most" -- "$STC" check "$TMP/fault"
  ;;
tasks)
  project inject <<'EOF'
[[task]]
name = "Fast"
interval = "1ms, PRIORITY := 3); TASK Evil(INTERVAL := T#1ms"
programs = ["MAIN"]
EOF
  expect interval-injection 1 "project.toml:3:12: error: \[\[task\]\] interval: '1ms, PRIORITY := 3\); TASK Evil\(INTERV\.\.\.': a number is expected before ','" -- "$STC" check "$TMP/inject"
  project inject2 <<<'[[task]]
name = "Fast"
event = "go); TASK Evil(SINGLE := go"
programs = ["MAIN"]'
  expect event-injection 1 "\[\[task\]\] event = .*a variable name is expected" -- "$STC" check "$TMP/inject2"
  project inject3 <<<'[[task]]
name = "Fast"
interval = "1ms"
programs = ["MAIN : MAIN; PROGRAM X WITH Fast"]'
  expect program-injection 1 "\[\[task\]\] programs = .*an ST name is expected" -- "$STC" check "$TMP/inject3"
  project inject4 <<<'[[task]]
name = "Fast(INTERVAL := T#1ms); TASK Evil"
interval = "1ms"
programs = ["MAIN"]'
  expect name-injection 1 "\[\[task\]\] name = .*an ST name is expected" -- "$STC" check "$TMP/inject4"
  project keyword <<<'[[task]]
name = "END_IF"
interval = "1ms"
programs = ["MAIN"]'
  expect task-keyword 1 "project.toml:2:8: error: \[\[task\]\] name = \"END_IF\": 'END_IF' is an ST keyword and cannot name a task" -- "$STC" check "$TMP/keyword"
  project keyword2 <<<'[[task]]
name = "Fast"
interval = "1ms"
programs = ["while"]'
  expect program-keyword 1 "project.toml:4:13: error: \[\[task\]\] programs = \"while\": 'while' is an ST keyword" -- "$STC" check "$TMP/keyword2"
  project prio <<<'[[task]]
name = "Fast"
interval = "1ms"
priority = 99
programs = ["MAIN"]'
  expect priority-range 1 "project.toml:4:12: error: \[\[task\]\] priority = 99: out of range \(must be >= 0 and <= 31\)" -- "$STC" check "$TMP/prio"
  project both <<<'[[task]]
name = "Fast"
interval = "1ms"
event = "go"
programs = ["MAIN"]'
  expect interval-and-event 1 "\[\[task\]\] needs exactly one of interval or event" -- "$STC" check "$TMP/both"
  project twice <<<'[[task]]
name = "Fast"
interval = "1ms"
programs = ["MAIN"]
[[task]]
name = "FAST"
interval = "2ms"
programs = ["MAIN"]'
  expect task-name-twice 1 "project.toml:6:8: error: \[\[task\]\] name = \"FAST\" is given twice \(first at .*project.toml:2:8" -- "$STC" check "$TMP/twice"
  project good <<<'[[task]]
name = "Fast"
interval = "T#2ms"
priority = 1
programs = ["MAIN"]'
  expect valid-tasks 0 "MAIN.n = 5" -- "$STC" run "$TMP/good" --for 10ms --watch MAIN.n
  project config <<<'[[task]]
name = "Fast"
interval = "2ms"
programs = ["MAIN"]'
  cat >"$TMP/config/src/Config.st" <<'EOF'
CONFIGURATION Cell
  RESOURCE Cpu ON PLC
    TASK Slow(INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM Main WITH Slow : MAIN;
  END_RESOURCE
END_CONFIGURATION
EOF
  expect tasks-and-configuration 1 "Config.st:1:1: error: this CONFIGURATION and the \[\[task\]\] tables of .*config/project.toml:1:1 both define the tasks" -- "$STC" check "$TMP/config"
  ;;
files)
  project f <<<''
  mkfifo "$TMP/f/scenarios/fifo.toml"
  expect scenario-fifo 1 "scenarios/fifo.toml: error: is a FIFO \(named pipe\), not a file" -- "$STC" test "$TMP/f"
  rm "$TMP/f/scenarios/fifo.toml"
  mkdir "$TMP/f/scenarios/dir.toml"
  expect scenario-directory 1 "scenarios/dir.toml: error: is a directory, not a file" -- "$STC" test "$TMP/f"
  expect scenario-directory-counted 1 "^1 passed, 1 failed" -- "$STC" test "$TMP/f"
  rmdir "$TMP/f/scenarios/dir.toml"
  ln -s loop.toml "$TMP/f/scenarios/loop.toml"
  expect scenario-link-loop 1 "scenarios/loop.toml: error: is a symbolic link loop" -- "$STC" test "$TMP/f"
  rm "$TMP/f/scenarios/loop.toml"
  printf 'duration = "10ms"\ntrace = ["MAIN.n"]\n' >"$TMP/f/scenarios/golden.toml"
  mkdir -p "$TMP/f/expected"
  mkfifo "$TMP/f/expected/golden.csv"
  expect golden-fifo 1 "expected/golden.csv is a FIFO \(named pipe\), not a file" -- "$STC" test "$TMP/f"
  expect golden-fifo-update 1 "expected/golden.csv is a FIFO \(named pipe\), not a file" -- "$STC" test --update "$TMP/f"
  rm "$TMP/f/expected/golden.csv"
  ln -s golden.csv "$TMP/f/expected/golden.csv"
  expect golden-link-loop 1 "expected/golden.csv is a symbolic link loop" -- "$STC" test "$TMP/f"
  rm "$TMP/f/expected/golden.csv" "$TMP/f/scenarios/golden.toml"
  mkfifo "$TMP/retain"
  expect retain-fifo 2 "--retain: '.*retain' is a FIFO \(named pipe\), not a file" -- "$STC" run "$TMP/f" --cycles 1 --retain "$TMP/retain"
  expect retain-directory 2 "--retain: .* is a directory, not a file" -- "$STC" run "$TMP/f" --cycles 1 --retain "$TMP"
  ln -s loop.st "$TMP/f/src/loop.st"
  expect source-link-loop 1 "f/src/loop.st: is a symbolic link loop" -- "$STC" check "$TMP/f"
  expect source-link-loop-test 1 "f/src/loop.st: is a symbolic link loop" -- "$STC" test "$TMP/f"
  rm "$TMP/f/src/loop.st"
  mkfifo "$TMP/f/src/fifo.st"
  expect source-fifo 1 "f/src/fifo.st: is a FIFO \(named pipe\), not a file" -- "$STC" check "$TMP/f"
  expect source-fifo-file 1 "fifo.st: cannot open file: is a FIFO \(named pipe\), not a file" -- "$STC" check "$TMP/f/src/fifo.st"
  rm "$TMP/f/src/fifo.st"
  rm -rf "$TMP/f/scenarios"
  ln -s scenarios "$TMP/f/scenarios"
  expect scenarios-dir-link-loop 1 "scenarios: error: is a symbolic link loop, not a directory of scenarios" -- "$STC" test "$TMP/f"
  rm "$TMP/f/scenarios"
  touch "$TMP/f/scenarios"
  expect scenarios-dir-file 1 "scenarios: error: is a file, not a directory of scenarios" -- "$STC" test "$TMP/f"
  project p <<<''
  rm "$TMP/p/project.toml"
  mkfifo "$TMP/p/project.toml"
  expect project-fifo-check 1 "p/project.toml: is a FIFO \(named pipe\), not a file" -- "$STC" check "$TMP/p"
  expect project-fifo-test 1 "p/project.toml: is a FIFO \(named pipe\), not a file" -- "$STC" test "$TMP/p"
  expect project-fifo-run 1 "p/project.toml: is a FIFO" -- "$STC" run "$TMP/p" --cycles 1
  rm "$TMP/p/project.toml"
  ln -s project.toml "$TMP/p/project.toml"
  expect project-link-loop 1 "p/project.toml: is a symbolic link loop" -- "$STC" check "$TMP/p"
  rm "$TMP/p/project.toml"
  mkdir "$TMP/p/project.toml"
  expect project-directory 1 "p/project.toml: is a directory, not a file" -- "$STC" check "$TMP/p"
  rmdir "$TMP/p/project.toml"
  ln -s /dev/zero "$TMP/p/project.toml"
  expect project-device 1 "p/project.toml: is a character device, not a file" -- "$STC" check "$TMP/p"
  rm "$TMP/p/project.toml"
  rm -rf "$TMP/p/scenarios"
  ln -s /dev/null "$TMP/p/project.toml"
  expect project-device-no-scenarios 1 "p/project.toml: error: is a character device" -- "$STC" test "$TMP/p"
  expect project-device-no-scenarios-counted 1 "^0 passed, 1 failed" -- "$STC" test "$TMP/p"
  ;;
checks)
  project c <<<''
  for key in min max; do
    for v in nan inf -inf; do
      scenario c run <<<"duration = \"10ms\"
[[check]]
var = \"r\"
$key = $v"
      expect "$key-$v" 1 "scenarios/run.toml:4:[0-9]+: error: \[\[check\]\] $key = .*: the number must be finite" -- "$STC" test "$TMP/c"
    done
  done
  scenario c run <<<'duration = "10ms"
tolerance = nan'
  expect tolerance-nan 1 "scenarios/run.toml:2:13: error: tolerance = nan: the number must be finite" -- "$STC" test "$TMP/c"
  scenario c run <<<'duration = "10ms"
tolerance = -1.0'
  expect tolerance-negative 1 "tolerance = -1.0: out of range" -- "$STC" test "$TMP/c"
  scenario c run <<<'duration = "10ms"
[[check]]
at = "5ms"
var = "r"
equals = nan'
  expect equals-nan-float 1 "scenarios/run.toml:5:10: error: \[\[check\]\] equals = nan: the number must be finite" -- "$STC" test "$TMP/c"
  for v in NaN "-Inf" "1.0E+400"; do
    scenario c run <<<"duration = \"10ms\"
[[check]]
at = \"5ms\"
var = \"r\"
equals = \"$v\""
    expect "equals-'$v'" 1 "scenarios/run.toml:2:1: error: r: equals .*: a finite number is expected|error: r: .*" -- "$STC" test "$TMP/c"
  done
  scenario c run <<<'duration = "10ms"
[[check]]
var = "r"
min = 2.0
max = 1.0'
  expect min-above-max 1 "\[\[check\]\] max = 1.0 is less than min = 2.0" -- "$STC" test "$TMP/c"
  scenario c run <<<'cycles = -1'
  expect cycles-negative 1 "cycles = -1: out of range \(must be >= 1" -- "$STC" test "$TMP/c"
  scenario c run <<<'cycles = 100000000000000000'
  expect cycles-huge 1 "cycles = 100000000000000000: out of range" -- "$STC" test "$TMP/c"
  expect cli-cycles-1e20 2 "--cycles" -- "$STC" run "$TMP/c" --cycles 1e20
  expect cli-cycles-negative 2 "--cycles" -- "$STC" run "$TMP/c" --cycles -5
  expect cli-cycles-huge 2 "--cycles" -- "$STC" run "$TMP/c" --cycles 100000000000000000000
  expect cli-jobs-negative 2 "-j|--jobs" -- "$STC" test -j -1 "$TMP/c"
  expect cli-slice-negative 2 "--slice" -- "$STC" run "$TMP/c" --cycles 1 --slice -3
  {
    echo '[project]'
    echo 'libraries = ["codesys_sm3"]'
    for i in $(seq 10000); do printf '[[axis]]\nname = "Axis1"\n'; done
  } >"$TMP/axes.toml"
  project many <"$TMP/axes.toml"
  expect axes-same-name 1 "project.toml:6:8: error: \[\[axis\]\] name = \"Axis1\" is given twice \(first at .*project.toml:4:8" -- "$STC" check "$TMP/many"
  ;;
axes)
  # Each bad axis value (key = value, then the expected message) on a servo axis.
  while IFS='|' read -r key value message; do
    project ax <<EOF
[project]
libraries = ["codesys_sm3"]
[[axis]]
name = "Axis1"
$key = $value
EOF
    expect "axis-$key=$value" 1 "project.toml:5:[0-9]+: error: \[\[axis\]\] $message" -- "$STC" check "$TMP/ax"
  done <<'EOF'
kv|-100|kv = -100: out of range \(must be > 0 and <= 10000\)
kv|0|kv = 0: out of range
kv|nan|kv = nan: the number must be finite
max_velocity|-1|max_velocity = -1: out of range \(must be >= 0
max_velocity|inf|max_velocity = inf: the number must be finite
max_acceleration|-5.0|max_acceleration = -5.0: out of range
max_jerk|1e20|max_jerk = 1.*e\+20: out of range
period|nan|period = nan: the number must be finite
period|-360.0|period = -360.0: out of range
lag_time|-0.002|lag_time = -0.002: out of range
lag_time|inf|lag_time = inf: the number must be finite
increments_per_unit|0|increments_per_unit = 0: out of range \(must be > 0
following_error_limit|-1.0|following_error_limit = -1.0: out of range
sw_limit_positive|1e300|sw_limit_positive = 1.*e\+300: out of range
encoder_channel|5|encoder_channel = 5: out of range \(must be >= 0 and <= 2\)
encoder_channel|1.5|encoder_channel = 1.5: an integer is expected
home_switch|[5.0, 1.0]|home_switch = \[ 5.0, 1.0 \]: the first value must not be greater than the second
home_switch|[0.0, nan]|home_switch = nan: the number must be finite
gear_ratio|[0.0, 1.0]|gear_ratio = 0.0: out of range
drive|"lagg"|drive = "lagg": must be "ideal" or "lag"; did you mean "lag"\?
type|"servoo"|type = "servoo": must be "servo", "virtual", "encoder" or "pulse"; did you mean "servo"\?
ramp|"trapezoid"|ramp = "trapezoid": must be "trapez", "quadratic" or "quadratic_ramp"; did you mean "trapez"\?
unit|"m m"|unit = "m m": a unit of measure is expected \(e.g. "mm", "deg"\)
unit|""|unit = "": a unit of measure is expected
unit|"seventeen_chars_x"|unit = "seventeen_chars_x": a unit of measure is expected
unit|"a,b"|unit = "a,b": a unit of measure is expected
unit|5|unit = 5: a string is expected
EOF
  project order <<<'[project]
libraries = ["codesys_sm3"]
[[axis]]
name = "Axis1"
sw_limit_positive = -10.0
sw_limit_negative = 10.0'
  expect sw-limits-order 1 "project.toml:5:21: error: \[\[axis\]\] sw_limit_positive = -10.0 is less than sw_limit_negative = 10.0" -- "$STC" check "$TMP/order"
  project scale <<<'[project]
libraries = ["codesys_sm3"]
[[axis]]
name = "Axis1"
increments_per_unit = 1000
encoder_resolution = 131072'
  # kv against the owning task's cycle: kv x cycle >= 1 makes the sampled position loop run away.
  for case in "1ms 999 0" "1ms 1000 1" "4ms 500 1" "4ms 249 0"; do
    set -- $case
    project kv <<EOF
[project]
libraries = ["codesys_sm3"]
[[task]]
name = "Motion"
interval = "$1"
programs = ["MAIN"]
[[axis]]
name = "Axis1"
type = "servo"
drive = "lag"
kv = $2
EOF
    printf 'VAR_GLOBAL\n  Axis1 : AXIS_REF_SM3;\nEND_VAR\n' >"$TMP/kv/src/Axes.st"
    if [ "$3" = 0 ]; then
      expect "kv-$2-cycle-$1" 0 "" -- "$STC" run "$TMP/kv" --cycles 3
    else
      expect "kv-$2-cycle-$1" 1 "kv/project.toml:11:6: \\[\\[axis\\]\\] 'Axis1': kv = $2 with the T#$1 cycle of task 'Motion' makes the position loop unstable \\(kv x cycle time must be < 1: kv < [0-9]+\\)" -- "$STC" run "$TMP/kv" --cycles 3
    fi
  done
  expect scaling-twice 1 "project.toml:3:1: error: \[\[axis\]\]: give only one of increments_per_unit or encoder_resolution" -- "$STC" check "$TMP/scale"
  # [[group]]: the schema (empty axes, a typo) and the start checks (an axis listed twice, one
  # that is no [[axis]], a name that is no group variable, members of two tasks).
  group_project() {
    project grp
    printf 'VAR_GLOBAL\n  Axis1, Axis2 : AXIS_REF_SM3;\n  G : AXIS_GROUP_REF_SM3;\nEND_VAR\n' >"$TMP/grp/src/Axes.st"
  }
  group_project <<<'[project]
libraries = ["codesys_sm3"]
[[group]]
name = "G"
axes = []'
  expect group-axes-empty 1 "project.toml:5:8: error: \[\[group\]\] axes: must not be empty" -- "$STC" check "$TMP/grp"
  group_project <<<'[project]
libraries = ["codesys_sm3"]
[[group]]
name = "G"
axis = ["Axis1"]'
  expect group-key-typo 1 "project.toml:5:1: error: unknown key 'axis' in \[\[group\]\].*did you mean 'axes'" -- "$STC" check "$TMP/grp"
  for case in 'Axis1", "Axis1|listed twice' 'Axis1", "Axis3|Axis3. is not an \[\[axis\]\]'; do
    axes=${case%%|*}; msg=${case#*|}
    group_project <<EOF
[project]
libraries = ["codesys_sm3"]
[[axis]]
name = "Axis1"
[[axis]]
name = "Axis2"
[[group]]
name = "G"
axes = ["$axes"]
EOF
    expect "group-${axes//[^A-Za-z0-9]/-}" 1 "project.toml:7:1: \[\[group\]\] 'G': .*$msg" -- "$STC" run "$TMP/grp" --cycles 3
  done
  group_project <<<'[project]
libraries = ["codesys_sm3"]
[[axis]]
name = "Axis1"
[[group]]
name = "Axis1"
axes = ["Axis1"]'
  expect group-not-a-group 1 "\[\[group\]\] 'Axis1' has no axis group variable of that name" -- "$STC" run "$TMP/grp" --cycles 3
  group_project <<<'[project]
libraries = ["codesys_sm3"]
[[task]]
name = "Fast"
interval = "1ms"
programs = ["MAIN"]
[[task]]
name = "Slow"
interval = "10ms"
priority = 5
programs = ["Other"]
[[axis]]
name = "Axis1"
task = "Fast"
[[axis]]
name = "Axis2"
task = "Slow"
[[group]]
name = "G"
axes = ["Axis1", "Axis2"]'
  printf 'PROGRAM Other\nEND_PROGRAM\n' >>"$TMP/grp/src/Axes.st"
  expect group-two-tasks 1 "\[\[group\]\] 'G': its axes belong to different tasks" -- "$STC" run "$TMP/grp" --cycles 3
  ;;
*)
  echo "unknown group $GROUP"; exit 2 ;;
esac
[ $failures -eq 0 ] || { echo "$failures case(s) failed"; exit 1; }
echo "OK"
