#!/usr/bin/env bash
# -g: the object's DWARF line table names the ST file and its statement lines.
# (grep -q reads a here-string: `echo | grep -q` fails under pipefail when grep exits early.)
set -euo pipefail
stc=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$stc" build -g -O0 "$src" -o "$tmp/out.o"
dump=$(llvm-dwarfdump-19 --debug-line "$tmp/out.o")
grep -q "name: \"$(basename "$src")\"" <<< "$dump" || { echo "file name missing"; exit 1; }
# Every line that starts a statement of the FB body must appear in the table.
for line in 13 14 15; do
  grep -Eq "^0x[0-9a-f]+ +$line +[0-9]+ " <<< "$dump" || { echo "line $line missing"; exit 1; }
done
"$stc" build -O0 "$src" -o "$tmp/nodebug.o"
nodebug=$(llvm-dwarfdump-19 --debug-line "$tmp/nodebug.o")
if grep -q "name: \"$(basename "$src")\"" <<< "$nodebug"; then echo "line table without -g"; exit 1; fi
echo ok
