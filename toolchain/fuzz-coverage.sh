#!/usr/bin/env bash
# Line and branch coverage that the fuzz corpora reach in the Dynamixel code (packet parser,
# codecs, virtual buses): builds the fuzz targets with clang source-based coverage
# (STRIDE_FUZZ_COVERAGE, build/fuzz-coverage), runs every input of each target's corpus once
# (libFuzzer -runs=0), merges the profiles and prints llvm-cov's per-file report. The
# annotated sources (execution and branch counts) go to build/fuzz-coverage/coverage.txt.
#
#   toolchain/fuzz-coverage.sh           seed corpus + what toolchain/fuzz.sh added
#                                        (build/fuzz/corpus/<target>)
#   toolchain/fuzz-coverage.sh --seeds   the committed seed corpus alone
set -euo pipefail
cd "$(dirname "$0")/.."
seeds_only=0
[[ "${1:-}" == "--seeds" ]] && seeds_only=1
build=build/fuzz-coverage
# Absolute source paths in the coverage mapping (ccache would rewrite them relative to its
# CCACHE_BASEDIR), so that llvm-cov can select the files below.
unset CCACHE_BASEDIR
profdata=$(command -v llvm-profdata-14 || command -v llvm-profdata)
llvm_cov=$(command -v llvm-cov-14 || command -v llvm-cov)

CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSTRIDE_FIRMWARE_ONLY=ON -DSTRIDE_BUILD_FUZZ=ON -DSTRIDE_FUZZ_COVERAGE=ON \
  -DSTRIDE_BUILD_BENCH=OFF >/dev/null
targets=$(cd tests/fuzz && ls fuzz_*.cpp | sed 's/\.cpp$//')
# shellcheck disable=SC2086
cmake --build "$build" -j "$(nproc)" --target $targets >/dev/null

rm -rf "$build/profiles"
mkdir -p "$build/profiles"
objects=()
for t in $targets; do
  dirs=("tests/fuzz/corpus/$t")
  if [[ $seeds_only == 0 && -d "build/fuzz/corpus/$t" ]]; then dirs+=("build/fuzz/corpus/$t"); fi
  inputs=$(find "${dirs[@]}" -type f | wc -l)
  echo "$t: $inputs inputs from ${dirs[*]}"
  LLVM_PROFILE_FILE="$build/profiles/$t.profraw" "$build/fuzz/$t" -runs=0 -max_len=4096 \
    "${dirs[@]}" >"$build/$t.log" 2>&1
  objects+=(-object "$build/fuzz/$t")
done
"$profdata" merge -sparse "$build"/profiles/*.profraw -o "$build/fuzz.profdata"
sources=()
for f in packet_parser codec_v1 codec_v2 virtual_bus virtual_bus_v2 virtual_bus_faults; do
  sources+=("$PWD/hal/src/dynamixel/$f.cpp")
done
"$llvm_cov" show -instr-profile="$build/fuzz.profdata" "${objects[@]:1}" -show-branches=count \
  "${sources[@]}" >"$build/coverage.txt"
"$llvm_cov" report -instr-profile="$build/fuzz.profdata" "${objects[@]:1}" "${sources[@]}"
echo "annotated sources: $build/coverage.txt"
