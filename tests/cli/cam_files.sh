#!/usr/bin/env bash
# Hostile files for SMC_ReadCAM / SMC_WriteCAM and project.toml [[cam]] (docs/motion-cam.md):
# a FIFO, a directory, an empty file, garbage, a sparse 100 MB file, a symbolic link out of the
# project, a link inside it.  Each gives its ErrorID (or a load error), never a hang or a signal.
set -euo pipefail
stc=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/p" "$tmp/p/dir"
mkfifo "$tmp/p/fifo.cam"
: > "$tmp/p/empty.cam"
head -c 4096 /dev/urandom > "$tmp/p/garbage.cam"
truncate -s 100M "$tmp/p/huge.cam"
printf 'STC-CAM 1\ntype table2d\npoints 2\n0 0\n10 5\ntappets 0\nend\n' > "$tmp/outside.cam"
ln -s ../outside.cam "$tmp/p/escape.cam"
printf 'STC-CAM 1\ntype table2d\npoints 2\n0 0\n10 5\ntappets 0\nend\n' > "$tmp/p/good.cam"
ln -s good.cam "$tmp/p/inside.cam"
cat > "$tmp/p/main.st" <<'ST'
VAR_GLOBAL
  pts : ARRAY[0..1] OF SMC_CAMXYVA := [(dX := 0), (dX := 10, dY := 5)];
  cam : MC_CAM_REF := (nElements := 2);
END_VAR
PROGRAM MAIN
VAR
  rd : ARRAY[0..7] OF SMC_ReadCAM;
  wr : ARRAY[0..2] OF SMC_WriteCAM;
  e : ARRAY[0..10] OF INT;
  i : INT;
END_VAR
cam.pce := ADR(pts);
rd[0](bExecute := TRUE, sFileName := 'fifo.cam');
rd[1](bExecute := TRUE, sFileName := 'dir');
rd[2](bExecute := TRUE, sFileName := 'empty.cam');
rd[3](bExecute := TRUE, sFileName := 'garbage.cam');
rd[4](bExecute := TRUE, sFileName := 'huge.cam');
rd[5](bExecute := TRUE, sFileName := 'escape.cam');
rd[6](bExecute := TRUE, sFileName := 'inside.cam');
rd[7](bExecute := TRUE, sFileName := '');
wr[0](CAM := cam, bExecute := TRUE, sFileName := 'fifo.cam');
wr[1](CAM := cam, bExecute := TRUE, sFileName := 'dir');
wr[2](CAM := cam, bExecute := TRUE, sFileName := 'escape.cam');
FOR i := 0 TO 7 DO e[i] := rd[i].ErrorID; END_FOR
FOR i := 0 TO 2 DO e[8 + i] := wr[i].ErrorID; END_FOR
END_PROGRAM
ST
out=$(timeout 20 "$stc" run "$tmp/p/main.st" --dialect=codesys --lib codesys_sm3 --cycles 2 --watch MAIN.e)
expect='MAIN.e = [2200, 2200, 2202, 2202, 2201, 2200, 0, 2200, 2200, 2200, 2200]'
[ "$out" = "$expect" ] || { echo "got:      $out"; echo "expected: $expect"; exit 1; }
# The outside file was not overwritten through the link.
grep -q 'points 2' "$tmp/outside.cam" && ! grep -q 'xyva' "$tmp/outside.cam" || { echo "wrote outside the project"; exit 1; }
# project.toml [[cam]] with a FIFO, a link out of the project, a 100 MB file: load errors, no hang.
mkdir "$tmp/p/src"
cp "$tmp/p/main.st" "$tmp/p/src/"
for f in fifo.cam escape.cam huge.cam; do
  printf '[build]\ndialect = "codesys"\n\n[[cam]]\nvar = "cam"\nfile = "%s"\n' "$f" > "$tmp/p/project.toml"
  if msg=$(timeout 20 "$stc" run "$tmp/p" --lib codesys_sm3 --cycles 1 2>&1); then echo "[[cam]] file = $f was accepted"; exit 1; fi
  grep -q "cam file" <<< "$msg" || { echo "no cam-file error for $f: $msg"; exit 1; }
done
echo ok
