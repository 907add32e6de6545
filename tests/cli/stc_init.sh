#!/usr/bin/env bash
# stc init (tools/stc/Init.cpp): the new project passes stc check --Werror and stc test at once,
# for the default (one codesys_sm3 axis), three Leadshine axes and no axis; it never overwrites.
set -uo pipefail
STC=$1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAILED: $*"; exit 1; }
for args in "" "--axes 3 --lib leadshine" "--axes 0"; do
  dir="$TMP/p_${#args}"
  # shellcheck disable=SC2086
  "$STC" init "$dir" $args > "$TMP/out" 2>&1 || { cat "$TMP/out"; fail "init $args"; }
  [ -f "$dir/expected/smoke.csv" ] || fail "init $args: no golden trace"
  "$STC" check --Werror "$dir" > "$TMP/out" 2>&1 || { cat "$TMP/out"; fail "check after init $args"; }
  (cd "$dir" && "$STC" test) > "$TMP/out" 2>&1 || { cat "$TMP/out"; fail "test after init $args"; }
  grep -q "1 passed, 0 failed" "$TMP/out" || fail "test after init $args: $(cat "$TMP/out")"
done
grep -q 'name = "Axis3"' "$TMP/p_24/project.toml" || fail "three axes"
# Never over an existing project; bad arguments are exit 2.
"$STC" init "$TMP/p_0" > "$TMP/out" 2>&1; [ $? -eq 2 ] || fail "init over a project"
grep -q "never overwrites" "$TMP/out" || fail "overwrite message"
"$STC" init "$TMP/bad name" > /dev/null 2>&1; [ $? -eq 2 ] || fail "a name with a blank"
"$STC" init "$TMP/q" --axes 17 > /dev/null 2>&1; [ $? -eq 2 ] || fail "--axes 17"
echo "ok"
