#!/usr/bin/env bash
# stc build writes a relocatable x86-64 ELF object (and its default name).
set -euo pipefail
stc=$1 project=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$stc" build "$project" -o "$tmp/out.o"
magic=$(head -c 4 "$tmp/out.o" | od -An -c | tr -d ' ')
[ "$magic" = '177ELF' ] || { echo "not an ELF file: $magic"; exit 1; }
# e_type (bytes 16-17) = 1: relocatable.
etype=$(od -An -t u2 -j 16 -N 2 "$tmp/out.o" | tr -d ' ')
[ "$etype" = 1 ] || { echo "e_type $etype, expected 1 (ET_REL)"; exit 1; }
(cd "$tmp" && "$stc" build "$project" && [ -s "$(basename "$project").o" ]) || { echo "default output name missing"; exit 1; }
echo ok
