#!/usr/bin/env bash
# stc check reads a project's G-code programs (nc/*, [[cnc_program]] files) only inside the
# project: a symbolic link leading out is an error naming it, and its text is never shown.
set -uo pipefail
STC=$1; SRC=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cp -r "$SRC" "$TMP/p"
echo "N10 G1 X1 F10 SECRET" > "$TMP/outside.cnc"
rm "$TMP/p/programs/part.txt"
ln -s "$TMP/outside.cnc" "$TMP/p/programs/part.txt"
mkdir -p "$TMP/p/nc"
ln -s "$TMP/outside.cnc" "$TMP/p/nc/evil.cnc"
out=$("$STC" check "$TMP/p" 2>&1); rc=$?
[ $rc -eq 1 ] || { echo "exit $rc, expected 1: $out"; exit 1; }
grep -q "nc/evil.cnc: leads outside the project directory" <<< "$out" || { echo "no error for nc/evil.cnc: $out"; exit 1; }
grep -q "programs/part.txt: leads outside the project directory" <<< "$out" || { echo "no error for part.txt: $out"; exit 1; }
! grep -q SECRET <<< "$out" || { echo "the outside file was read: $out"; exit 1; }
out=$("$STC" run "$TMP/p" --cycles 1 2>&1); rc=$?
[ $rc -ne 0 ] || { echo "stc run accepted it: $out"; exit 1; }
! grep -q SECRET <<< "$out" || { echo "stc run read the outside file: $out"; exit 1; }
echo ok
