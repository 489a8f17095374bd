#!/usr/bin/env bash
# The main job from a fresh machine: installs the dependencies, builds the release preset and
# runs the demo. Until the optimiser lands the demo is the firmware loop on the test HAL, paced
# by the real clock for a few seconds, printing its loop statistics.
set -euo pipefail
cd "$(dirname "$0")/.."

toolchain/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

echo "== stride-fw on the test HAL for 3 s at 100 Hz"
build/release/bin/stride-fw --hal test --ticks 300
