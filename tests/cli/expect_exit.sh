#!/usr/bin/env bash
# usage: expect_exit.sh CODE [PATTERN] -- COMMAND...
# Runs COMMAND; passes if it exits with CODE and (if given) its combined
# output matches the extended regular expression PATTERN.
set -uo pipefail
code=$1; shift
pattern=""
if [ "$1" != "--" ]; then pattern=$1; shift; fi
shift
out=$("$@" 2>&1); rc=$?
if [ "$rc" -ne "$code" ]; then echo "exit status $rc, expected $code"; echo "$out" | tail -20; exit 1; fi
if [ -n "$pattern" ] && ! grep -Eq -e "$pattern" <<< "$out"; then echo "output does not match /$pattern/:"; echo "$out" | tail -20; exit 1; fi
exit 0
