#!/usr/bin/env bash
# Fuzzes the front end with libFuzzer for SECONDS (default 600).
# Builds build-fuzz/ with clang-19, ASan and UBSan; seeds from the test sources.
# Crashing inputs land in build-fuzz/crashes/; copy minimised ones to
# tests/fuzz/regressions/ so the test suite replays them.
#
# tools/fuzz.sh --config [SECONDS] [ARGS...]: the mutation fuzzer of project.toml and
# scenarios/*.toml instead (tools/fuzz_config.py on build/stc: mutated example projects
# through stc check / stc test; a signal, abort or timeout fails).
# tools/fuzz.sh --gcode [SECONDS]: the G-code lexer, parser and decoder (tests/fuzz/gcode_fuzz.cpp,
# docs/cnc.md); crashes land in build-fuzz/gcode-crashes/, minimised ones go to
# tests/fuzz/gcode_regressions/ (replayed by the fuzz/gcode-replay test).
# tools/fuzz.sh --path [SECONDS]: the path preprocessing chain ToolCorr -> AvoidLoop -> SmoothPath ->
# CheckVelocities (tests/fuzz/path_fuzz.cpp); crashes land in build-fuzz/path-crashes/, minimised ones
# go to tests/fuzz/path_regressions/ (replayed by the fuzz/path-replay test).
set -euo pipefail
cd "$(dirname "$0")/.."
configure_fuzz_build() {
  if [ ! -f build-fuzz/build.ninja ]; then
    CC=clang-19 CXX=clang++-19 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DSTC_FUZZ=ON -DSTC_SANITIZE=ON -DSTC_BENCHMARKS=OFF -DSTC_WERROR=OFF \
      -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link"
  fi
}
if [ "${1:-}" = "--gcode" ]; then
  SECONDS_TO_RUN=${2:-600}
  configure_fuzz_build
  cmake --build build-fuzz --target stc_fuzz_gcode
  mkdir -p build-fuzz/gcode-corpus build-fuzz/gcode-crashes
  find tests/cnc -name '*.cnc' -size -16k -exec cp {} build-fuzz/gcode-corpus/ \; 2>/dev/null || true
  build-fuzz/tests/fuzz/stc_fuzz_gcode build-fuzz/gcode-corpus tests/fuzz/gcode_regressions -max_len=4096 -timeout=10 \
    -rss_limit_mb=4096 -max_total_time="$SECONDS_TO_RUN" -artifact_prefix=build-fuzz/gcode-crashes/ -print_final_stats=1 2>&1 |
    tee build-fuzz/gcode-fuzz.log | tail -25
  exit 0
fi
if [ "${1:-}" = "--path" ]; then
  SECONDS_TO_RUN=${2:-600}
  configure_fuzz_build
  cmake --build build-fuzz --target stc_fuzz_path
  mkdir -p build-fuzz/path-corpus build-fuzz/path-crashes
  # Seeds: the test programs behind three option headers (four bytes, see path_fuzz.cpp): no
  # preprocessing; G41 radius 2 in TC_BLIND_POS with G51 and G61; G42 radius 0.5 in TC_RAMP_IN
  # with G52 and pre-acknowledged M functions.
  find tests/cnc tests/fuzz/gcode_regressions projects/*/nc -type f \( -name '*.cnc' -o -name '*.ngc' \) -size -4k |
    while read -r f; do
      i=0
      for h in '\x80\x00\x00\x13' '\xac\x0d\x04\x53' '\xca\x0a\x28\x93'; do
        { printf "$h"; cat "$f"; } > "build-fuzz/path-corpus/$(basename "$f")-$i"
        i=$((i + 1))
      done
    done
  build-fuzz/tests/fuzz/stc_fuzz_path build-fuzz/path-corpus tests/fuzz/path_regressions -max_len=4096 -timeout=10 \
    -rss_limit_mb=4096 -max_total_time="$SECONDS_TO_RUN" -artifact_prefix=build-fuzz/path-crashes/ -print_final_stats=1 2>&1 |
    tee build-fuzz/path-fuzz.log | tail -25
  exit 0
fi
if [ "${1:-}" = "--config" ]; then
  shift
  SECONDS_TO_RUN=${1:-600}
  shift || true
  tools/build.sh >/dev/null
  exec python3 tools/fuzz_config.py "$SECONDS_TO_RUN" --stc build/stc "$@"
fi
SECONDS_TO_RUN=${1:-600}
configure_fuzz_build
cmake --build build-fuzz --target stc_fuzz_frontend
mkdir -p build-fuzz/corpus build-fuzz/crashes
find tests projects stdlib-motion -name '*.st' -size -16k -exec cp {} build-fuzz/corpus/ \; 2>/dev/null || true
cp tests/fuzz/regressions/* build-fuzz/corpus/ 2>/dev/null || true
build-fuzz/tests/fuzz/stc_fuzz_frontend build-fuzz/corpus -max_len=8192 -timeout=10 -rss_limit_mb=4096 \
  -max_total_time="$SECONDS_TO_RUN" -artifact_prefix=build-fuzz/crashes/ -print_final_stats=1 2>&1 | tee build-fuzz/fuzz.log | tail -25
