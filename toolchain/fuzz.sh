#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz) with clang in a separate build directory, the code
# they call instrumented too (cmake/StrideFuzz.cmake), and runs each on a scratch copy of its
# committed seed corpus (tests/fuzz/corpus/<target>) with the dictionary
# tests/fuzz/dynamixel.dict. Fails on any crash, sanitizer report, failed check or leak.
# What each run added stays in build/fuzz/corpus/<target> (toolchain/fuzz-coverage.sh reads it).
#
#   toolchain/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default 20 s, every target)
#   toolchain/fuzz.sh --runs N [SECONDS] [TARGET...]        (N inputs per target, or SECONDS
#                                                           if that comes first)
set -euo pipefail
cd "$(dirname "$0")/.."
limit=()
if [[ "${1:-}" == "--runs" ]]; then
  limit=(-runs="${2:?--runs needs a count}")
  shift 2
fi
if [[ "${1:-}" =~ ^[0-9]+$ ]]; then
  limit+=(-max_total_time="$1")
  shift
elif [[ ${#limit[@]} -eq 0 ]]; then
  limit=(-max_total_time=20)
fi
build=build/fuzz
jobs=$(nproc)

CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSTRIDE_FIRMWARE_ONLY=ON -DSTRIDE_BUILD_FUZZ=ON -DSTRIDE_FUZZ_COVERAGE=OFF \
  -DSTRIDE_BUILD_BENCH=OFF >/dev/null
if [[ $# -gt 0 ]]; then
  targets="$*"
else
  targets=$(cd tests/fuzz && ls fuzz_*.cpp | sed 's/\.cpp$//')
fi
# shellcheck disable=SC2086
cmake --build "$build" -j "$jobs" --target $targets

# A 16 MB quarantine (ASan's default is 256 MB) still holds far more than one input frees, and
# keeps freed memory from being re-faulted in: the virtual bus targets run about 1.7x faster.
export ASAN_OPTIONS="${ASAN_OPTIONS:-quarantine_size_mb=16:malloc_context_size=10}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"

status=0
for t in $targets; do
  corpus="$build/corpus/$t"
  mkdir -p "$corpus"
  if [[ -d "tests/fuzz/corpus/$t" ]]; then
    cp -n tests/fuzz/corpus/"$t"/* "$corpus"/
  fi
  # Inputs up to 4 KiB for the parsers (twice their buffer: the full-buffer paths), 2 KiB for
  # the codecs (a maximal 2.0 packet), 1 KiB of host bytes for the virtual buses.
  case $t in
    fuzz_parser_*) max_len=4096 ;;
    fuzz_codec) max_len=2048 ;;
    *) max_len=1024 ;;
  esac
  echo "== $t (${limit[*]} -max_len=$max_len)"
  if ! "$build/fuzz/$t" "${limit[@]}" -max_len=$max_len -dict=tests/fuzz/dynamixel.dict \
      -print_final_stats=1 -artifact_prefix="$build/$t-" "$corpus" >"$build/$t.log" 2>&1; then
    echo "fuzz: $t FAILED (see $build/$t.log and $build/$t-*)" >&2
    tail -n 30 "$build/$t.log" >&2
    status=1
  elif grep -qE "runtime error|ERROR: [A-Za-z]+Sanitizer" "$build/$t.log"; then
    echo "fuzz: $t reported a sanitizer error (see $build/$t.log)" >&2
    grep -m 5 -E "runtime error|ERROR:" "$build/$t.log" >&2
    status=1
  else
    grep -E "^#[0-9]+[[:space:]]+DONE|stat::number_of_executed_units|stat::average_exec_per_sec" \
      "$build/$t.log" | tail -n 3
    echo "corpus: $(ls "$corpus" | wc -l) inputs"
  fi
done
exit $status
