#!/usr/bin/env bash
# Runtime checks appear in the IR by default and --no-checks removes them.
set -euo pipefail
stc=$1 src=$2
ir=$("$stc" build --emit llvm -O0 -o - "$src")
grep -q "__stc_fault" <<< "$ir" || { echo "no check in the default IR"; exit 1; }
unchecked=$("$stc" build --emit llvm -O0 --no-checks -o - "$src")
if grep -q "call void @__stc_fault" <<< "$unchecked"; then
  echo "--no-checks left a check"; exit 1
fi
echo ok
