#!/usr/bin/env bash
# The main demo: builds stc, runs the two-axis pick-and-place project
# (projects/pick_and_place: homing, then pick-and-place cycles) for 12 s of
# simulated time, prints the part count and axis states, and draws the axis
# positions, the gripper and the cell state into build/demo/pick_and_place.svg.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
mkdir -p build/demo
build/stc run projects/pick_and_place --for 12s \
  --watch GVL.nParts --watch Cell.eState --watch AxisX.nAxisState --watch AxisZ.nAxisState \
  --trace AxisX.fSetPosition,AxisZ.fSetPosition,AxisX.fSetVelocity,AxisZ.fSetVelocity,GVL.bGripper,GVL.bHomed,Cell.eState \
  --trace-out build/demo/pick_and_place.csv --plot build/demo/pick_and_place.svg
echo "demo: 12 s of projects/pick_and_place; plot in build/demo/pick_and_place.svg (open it in a browser),"
echo "      trace in build/demo/pick_and_place.csv; build/stc test projects/pick_and_place runs its scenarios"
