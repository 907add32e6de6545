#!/usr/bin/env bash
# The main demo: checks the demo project and prints the front end's figures.
# (Running and plotting it arrive with the virtual controller, issues 3 and 6.)
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
build/stc check --stats projects/conveyor_demo
echo "demo: projects/conveyor_demo checks clean"
