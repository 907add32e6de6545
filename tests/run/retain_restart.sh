#!/usr/bin/env bash
# RETAIN across restarts, and the warm-start test: a run killed with
# SIGKILL at a random moment leaves a retain file that is either the
# previous complete one or a new complete one, never torn.
set -euo pipefail
stc=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/ret.st" <<'ST'
VAR_GLOBAL RETAIN
  a, b : UDINT;
END_VAR
PROGRAM MAIN
a := a + 1;
b := b + 1;
END_PROGRAM
ST
# (1) Two runs of 1 s: the second continues from the first.
"$stc" run "$tmp/ret.st" --for 1s --retain "$tmp/r.dat" >/dev/null
out=$("$stc" run "$tmp/ret.st" --for 1s --retain "$tmp/r.dat" --watch a --watch b)
[ "$out" = $'a = 2000\nb = 2000' ] || { echo "restart: got '$out'"; exit 1; }
# --cold restores PERSISTENT only: RETAIN starts again.
out=$("$stc" run "$tmp/ret.st" --cycles 1 --cold --retain "$tmp/c.dat" --watch a)
[ "$out" = "a = 1" ] || { echo "cold: got '$out'"; exit 1; }
# (2) Killed runs: the file always holds a consistent, non-empty state.
rm -f "$tmp/r.dat"
prev=0
for i in $(seq 1 10); do
  "$stc" run "$tmp/ret.st" --for 1h --realtime --retain "$tmp/r.dat" --retain-every 10ms >/dev/null 2>&1 &
  pid=$!
  sleep "0.$(( (RANDOM % 28) + 2 ))"
  kill -9 "$pid"
  wait "$pid" 2>/dev/null || true
  out=$("$stc" run "$tmp/ret.st" --cycles 0 --retain "$tmp/r.dat" --watch a --watch b 2>&1)
  a=$(echo "$out" | sed -n 's/^a = //p')
  b=$(echo "$out" | sed -n 's/^b = //p')
  if [ -z "$a" ] || [ "$a" != "$b" ] || [ "$a" -lt "$prev" ]; then
    echo "kill $i: inconsistent retain state: $out"
    exit 1
  fi
  prev=$a
  [ ! -e "$tmp/r.dat.tmp" ] || { echo "kill $i: a leftover .tmp survived a start"; exit 1; }
done
[ "$prev" -gt 0 ] || { echo "nothing was ever saved"; exit 1; }
echo "retain: restart ok; 10 killed runs left consistent states (last a = b = $prev)"
