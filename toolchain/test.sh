#!/usr/bin/env bash
# The whole test suite from a fresh machine: installs the dependencies, builds the unit tests
# with AddressSanitizer + UndefinedBehaviorSanitizer and runs them, builds the release preset
# and runs the integration tests (simulation, pseudo-terminal end-to-end runs), fuzzes the
# Dynamixel parsers briefly, then
# cross-compiles the firmware for aarch64 (tests under qemu-user) and statically for the igus
# PC (tests, staged install).
# Exits non-zero if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

toolchain/install-deps.sh --cross

echo "== unit tests (asan preset)"
cmake --preset asan >/dev/null
cmake --build --preset asan -j "$jobs" --target stride_unit_tests
ctest --preset asan -j "$jobs"

echo "== fuzzing the Dynamixel parsers, codecs and virtual buses (libFuzzer, 12 s per target)"
toolchain/fuzz.sh 12

echo "== integration tests (release preset)"
cmake --preset release >/dev/null
cmake --build --preset release -j "$jobs"
ctest --preset release -L integration -j "$jobs" --no-tests=ignore

echo "== firmware for aarch64 (cross-compiled, unit tests under qemu-user)"
cmake --preset aarch64 >/dev/null
cmake --build --preset aarch64 -j "$jobs"
ctest --preset aarch64 -j "$jobs"

echo "== static firmware for the igus PC, and its staged install"
cmake --preset igus-pc >/dev/null
cmake --build --preset igus-pc -j "$jobs"
ctest --preset igus-pc -j "$jobs"
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
cmake --install build/igus-pc --prefix "$stage" --strip >/dev/null
for f in bin/stride-fw share/stride/config/servo_table.json lib/systemd/system/stride-fw.service \
         etc/default/stride-fw; do
  [[ -e "$stage/$f" ]] || { echo "install: $f missing from the staged tree" >&2; exit 1; }
done
(cd / && "$stage/bin/stride-fw" --hal test --ticks 10 --no-rt --json >/dev/null)
echo "install: staged tree complete, static stride-fw runs from it"
