#!/usr/bin/env bash
# The main demo: builds stc, checks the conveyor project (its standard FBs
# run with issue 4), and runs the mixer project on the simulated controller
# for 2 s, printing watched variables, task statistics and a VCD trace.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
build/stc check --stats projects/conveyor_demo
echo "demo: projects/conveyor_demo checks clean"
mkdir -p build/demo
build/stc run projects/mixer_demo --for 2s --stats \
  --watch GVL.batches --watch Control.state --watch GVL.level --watch GVL.flowPulses \
  --trace GVL.level,GVL.inletOpen,GVL.mixerOn,GVL.outletOpen --trace-out build/demo/mixer.vcd
echo "demo: projects/mixer_demo ran 2 s of simulated time; trace in build/demo/mixer.vcd (open it in GTKWave)"
