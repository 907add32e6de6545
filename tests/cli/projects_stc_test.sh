#!/usr/bin/env bash
# ctest projects/stc-test: stc test over every project in projects/ that has
# a scenarios/ folder.  With none, an empty run must still succeed.
# Usage: projects_stc_test.sh STC PROJECTS_DIR
set -u
STC=$1
DIR=$2
dirs=()
for d in "$DIR"/*/; do
  [ -f "$d/project.toml" ] && [ -d "$d/scenarios" ] && dirs+=("${d%/}")
done
if [ ${#dirs[@]} -eq 0 ]; then
  echo "no project in $DIR has scenarios/; checking that an empty run succeeds"
  out=$("$STC" test "$DIR"/*/ 2>&1) || { echo "$out"; echo "FAILED: empty run exited non-zero"; exit 1; }
  echo "$out"
  [[ "$out" == *"0 passed, 0 failed"* ]] || { echo "FAILED: no '0 passed, 0 failed'"; exit 1; }
  exit 0
fi
exec "$STC" test "${dirs[@]}"
