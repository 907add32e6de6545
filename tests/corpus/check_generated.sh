#!/usr/bin/env bash
# Generates a corpus with a tools/gen_*.py script and checks it with stc.
# usage: check_generated.sh STC GENERATOR OUTDIR [generator args...]
# Fails on any error or warning: the generated code is meant to be clean.
set -euo pipefail
stc=$1 gen=$2 out=$3
shift 3
rm -rf "$out"
python3 -B "$gen" "$out" "$@" > /dev/null
log=$("$stc" check --stats "$out" 2>&1) || { echo "$log" | tail -40; exit 1; }
echo "$log" | tail -3
if grep -q "warning:" <<< "$log"; then echo "unexpected warnings"; exit 1; fi
