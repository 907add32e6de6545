#!/usr/bin/env bash
# A deliberately broken copy of an example project (one constant changed)
# must make `stc test` fail with a readable diff: for
# each differing variable with its first and last time, expected vs actual.
# Usage: broken_project.sh STC PROJECT_DIR FILE 'SED-EXPR'
set -u
STC=$1 SRC=$2 FILE=$3 EXPR=$4
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cp -r "$SRC" "$TMP/p"
sed -i "$EXPR" "$TMP/p/$FILE"
if cmp -s "$SRC/$FILE" "$TMP/p/$FILE"; then echo "FAILED: the sed expression changed nothing"; exit 1; fi
out=$("$STC" test "$TMP/p" 2>&1); rc=$?
echo "$out"
[ $rc -eq 1 ] || { echo "FAILED: exit $rc, expected 1"; exit 1; }
for want in "FAIL p/" "rows differ, first at T#" "expected " ", actual " "0 passed, "; do
  [[ "$out" == *"$want"* ]] || { echo "FAILED: output lacks '$want'"; exit 1; }
done
echo "OK"
