#!/usr/bin/env bash
# Determinism across optimisation levels: the multi-task project gives the
# same trace bytes at -O0, -O1 (default) and -O3.
set -euo pipefail
stc=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for o in 0 1 3; do
  "$stc" run "$src" --testlib -O$o --for 200ms --trace fast.x,fast.r,slow.y,ev.n,GVL_trig --trace-out "$tmp/O$o.csv" >/dev/null
done
cmp "$tmp/O0.csv" "$tmp/O1.csv"
cmp "$tmp/O0.csv" "$tmp/O3.csv"
lines=$(wc -l <"$tmp/O0.csv")
[ "$lines" -eq 201 ] || { echo "expected 201 trace lines, got $lines"; exit 1; }
echo "identical traces at -O0, -O1, -O3 ($lines lines)"
