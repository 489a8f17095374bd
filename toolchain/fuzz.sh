#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz) with clang in a separate build directory and runs
# each for a short time. Fails on any crash, sanitizer report or failed check.
#
#   toolchain/fuzz.sh [SECONDS_PER_TARGET]      (default 20)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
build=build/fuzz
jobs=$(nproc)

CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSTRIDE_FIRMWARE_ONLY=ON -DSTRIDE_BUILD_FUZZ=ON -DSTRIDE_BUILD_BENCH=OFF >/dev/null
targets=$(cd tests/fuzz && ls fuzz_*.cpp | sed 's/\.cpp$//')
# shellcheck disable=SC2086
cmake --build "$build" -j "$jobs" --target $targets

status=0
for t in $targets; do
  corpus="$build/corpus/$t"
  mkdir -p "$corpus"
  echo "== $t (${seconds}s)"
  if ! "$build/fuzz/$t" -max_total_time="$seconds" -max_len=2048 -print_final_stats=1 \
      -artifact_prefix="$build/$t-" "$corpus" 2>"$build/$t.log"; then
    echo "fuzz: $t FAILED (see $build/$t.log and $build/$t-*)" >&2
    tail -n 30 "$build/$t.log" >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|Done" "$build/$t.log" | tail -n 2
  fi
done
exit $status
