#!/usr/bin/env bash
# Installs every Debian 12 package that building and testing stc needs.
# Idempotent: does nothing (and needs no network) when all are installed.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build ccache python3 git
  antlr4 libantlr4-runtime-dev            # grammar tool (4.7.2) and C++ runtime (4.9)
  llvm-19-dev llvm-19-tools               # code generation; FileCheck, llvm-dwarfdump for tests
  libboost-context-dev                    # task fibers in the virtual controller
  libeigen3-dev                           # kinematic models (stdlib-motion/kinematics)
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libtomlplusplus-dev libfmt-dev nlohmann-json3-dev
  libpugixml-dev                          # PLCopen XML and TwinCAT import/export
  libjemalloc-dev                         # allocator for the front end
  clang-19 libclang-rt-19-dev             # libFuzzer target (tools/fuzz.sh)
)

missing=()
for p in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == *"install ok installed"* ]] || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages are installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
