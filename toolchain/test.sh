#!/usr/bin/env bash
# The whole test suite from a fresh machine: installs the dependencies, builds the unit tests
# with AddressSanitizer + UndefinedBehaviorSanitizer and runs them, then builds the release
# preset and runs the integration tests (simulation, pseudo-terminal end-to-end runs).
# Exits non-zero if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

toolchain/install-deps.sh

echo "== unit tests (asan preset)"
cmake --preset asan >/dev/null
cmake --build --preset asan -j "$jobs"
ctest --preset asan -j "$jobs"

echo "== integration tests (release preset)"
cmake --preset release >/dev/null
cmake --build --preset release -j "$jobs"
ctest --preset release -L integration -j "$jobs" --no-tests=ignore
