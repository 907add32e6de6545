#!/usr/bin/env bash
# The file sandbox (issue 14, item 3; docs/security.md "Files"): every file a program opens
# (SMC_AxisDiagnosticLog.WriteToFile, SMC_WriteCAM, SMC_ReadCAM) lives in the project's data
# directory ([project] data_dir, default <project>/data; stc run --data-dir). Absolute names,
# '..' escapes, symbolic links and hard links leading out of it are refused with the block's
# ErrorID (2100 the log, 2200 the cam blocks) and nothing outside is created or changed.
# stc test --update never writes outside the project (a symbolic link expected/ is refused).
set -euo pipefail
stc=$1
axis_demo=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
mkdir -p "$tmp/p/src" "$tmp/p/data" "$tmp/outside"
echo "precious" > "$tmp/victim.txt"
echo "precious" > "$tmp/victim2.txt"
ln -s "$tmp/outside" "$tmp/p/data/out"            # a directory link out of the project
ln -s ../../victim.txt "$tmp/p/data/lnk.txt"      # a file link out of it
ln "$tmp/victim2.txt" "$tmp/p/data/hard.txt"      # a hard link to a file outside
mkdir "$tmp/p/data/cams"
ln -s inside.cam "$tmp/p/data/cams/linked.cam"     # a link that stays inside: allowed
cat > "$tmp/p/project.toml" <<'TOML'
[project]
libraries = ["codesys_sm3"]

[[axis]]
name = "Axis1"
type = "servo"
increments_per_unit = 1000
TOML
cat > "$tmp/p/src/main.st" <<ST
VAR_GLOBAL
  Axis1 : AXIS_REF_SM3;
  pts : ARRAY[0..1] OF SMC_CAMXYVA := [(dX := 0), (dX := 10, dY := 5)];
  cam : MC_CAM_REF := (nElements := 2);
END_VAR
PROGRAM MAIN
VAR
  cycle : DINT;
  l : ARRAY[0..6] OF SMC_AxisDiagnosticLog;
  names : ARRAY[0..6] OF STRING := ['ok.log', '$tmp/abs.log', '../escape.log', 'out/x.log', 'lnk.txt', 'hard.txt', 'sub/../ok2.log'];
  le : ARRAY[0..6] OF SMC_ERROR;
  wr : ARRAY[0..3] OF SMC_WriteCAM;
  rd : ARRAY[0..3] OF SMC_ReadCAM;
  we, re : ARRAY[0..3] OF INT;
  i : INT;
END_VAR
cycle := cycle + 1;
cam.pce := ADR(pts);
FOR i := 0 TO 6 DO
  l[i](Axis := Axis1, bExecute := cycle >= 2, bCloseFile := cycle >= 10, sFileName := names[i], bSetPosition := TRUE);
  l[i].WriteToFile();
  IF l[i].bError THEN le[i] := l[i].ErrorID; END_IF
END_FOR
wr[0](CAM := cam, bExecute := TRUE, sFileName := 'cams/inside.cam');
wr[1](CAM := cam, bExecute := TRUE, sFileName := '../escape.cam');
wr[2](CAM := cam, bExecute := TRUE, sFileName := 'out/x.cam');
wr[3](CAM := cam, bExecute := TRUE, sFileName := '$tmp/abs.cam');
rd[0](bExecute := cycle >= 2, sFileName := 'cams/linked.cam');
rd[1](bExecute := TRUE, sFileName := '../project.toml');
rd[2](bExecute := TRUE, sFileName := '/etc/hostname');
rd[3](bExecute := TRUE, sFileName := 'lnk.txt');
FOR i := 0 TO 3 DO we[i] := wr[i].ErrorID; re[i] := rd[i].ErrorID; END_FOR
END_PROGRAM
ST
out=$(timeout 60 "$stc" run "$tmp/p" -w --cycles 20 --watch MAIN.le --watch MAIN.we --watch MAIN.re)
E=SMC_ERROR#SMC_ADL_FILE_CANNOT_BE_OPENED; N=SMC_ERROR#SMC_NO_ERROR
expect="MAIN.le = [$N, $E, $E, $E, $E, $E, $N]
MAIN.we = [0, 2200, 2200, 2200]
MAIN.re = [0, 2200, 2200, 2200]"
[ "$out" = "$expect" ] || { echo "got:"; echo "$out"; echo "expected:"; echo "$expect"; exit 1; }
# The good files are in the data directory; nothing was written outside.
[ -s "$tmp/p/data/ok.log" ] && [ -s "$tmp/p/data/ok2.log" ] && [ -s "$tmp/p/data/cams/inside.cam" ] || fail "the data directory lacks the good files"
[ "$(cat "$tmp/victim.txt")" = precious ] && [ "$(cat "$tmp/victim2.txt")" = precious ] || fail "a file outside was changed"
[ -z "$(ls -A "$tmp/outside")" ] || fail "a file was created through the directory link"
for f in "$tmp/abs.log" "$tmp/abs.cam" "$tmp/p/escape.log" "$tmp/p/escape.cam"; do [ ! -e "$f" ] || fail "created $f"; done

# [project] data_dir; the directory is created at the first write; stc run --data-dir wins.
sed -i 's/^\[project\]$/[project]\ndata_dir = "files"/' "$tmp/p/project.toml"
timeout 60 "$stc" run "$tmp/p" -w --cycles 20 >/dev/null
[ -s "$tmp/p/files/ok.log" ] || fail "data_dir = \"files\" was not used"
timeout 60 "$stc" run "$tmp/p" -w --cycles 20 --data-dir "$tmp/elsewhere" >/dev/null
[ -s "$tmp/elsewhere/ok.log" ] || fail "--data-dir was not used"
sed -i 's/^data_dir = "files"$/data_dir = 5/' "$tmp/p/project.toml"
if msg=$(timeout 60 "$stc" run "$tmp/p" -w --cycles 1 2>&1); then fail "data_dir = 5 was accepted"; fi
grep -q "\[project\] data_dir = 5: a string is expected" <<<"$msg" || fail "no data_dir message: $msg"

# stc test --update: a symbolic link expected/ leading out of the project is refused.
cp -r "$axis_demo" "$tmp/t"
rm -rf "$tmp/t/expected"
mkdir "$tmp/golden-elsewhere"
ln -s "$tmp/golden-elsewhere" "$tmp/t/expected"
if msg=$(timeout 120 "$stc" test "$tmp/t" --update 2>&1); then fail "stc test --update wrote through a link: $msg"; fi
grep -q "expected/move.csv not written: outside" <<<"$msg" || fail "no refusal message: $msg"
[ -z "$(ls -A "$tmp/golden-elsewhere")" ] || fail "stc test --update wrote outside the project"
# A real expected/ (created when missing) is written.
rm "$tmp/t/expected"
timeout 120 "$stc" test "$tmp/t" --update >/dev/null || fail "stc test --update in a plain project failed"
[ -s "$tmp/t/expected/move.csv" ] || fail "expected/move.csv not written"
echo "file sandbox: ok"
