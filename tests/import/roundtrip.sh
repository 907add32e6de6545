#!/usr/bin/env bash
# usage: roundtrip.sh STC SOURCE DURATION VAR,VAR,...
# Exports SOURCE (files or a project) as PLCopen XML, then runs SOURCE and the
# exported file with the same trace: the CSV files must be byte-identical.
set -euo pipefail
stc=$1 src=$2 dur=$3 vars=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$stc" export --color=never --plcopen "$tmp/out.xml" "$src"
"$stc" run --color=never "$src" --for "$dur" --trace "$vars" --trace-out "$tmp/a.csv" > "$tmp/a.out"
"$stc" run --color=never "$tmp/out.xml" --for "$dur" --trace "$vars" --trace-out "$tmp/b.csv" > "$tmp/b.out"
if ! cmp -s "$tmp/a.csv" "$tmp/b.csv"; then
  echo "traces differ:"; diff "$tmp/a.csv" "$tmp/b.csv" | head -20; exit 1
fi
rows=$(wc -l < "$tmp/a.csv")
[ "$rows" -gt 2 ] || { echo "trace too short ($rows lines)"; exit 1; }
# The export of the exported program is the same program again.
"$stc" export --color=never --plcopen "$tmp/out2.xml" "$tmp/out.xml"
"$stc" run --color=never "$tmp/out2.xml" --for "$dur" --trace "$vars" --trace-out "$tmp/c.csv" > /dev/null
cmp -s "$tmp/a.csv" "$tmp/c.csv" || { echo "second round trip differs"; exit 1; }
echo "round trip: $rows identical trace lines"
