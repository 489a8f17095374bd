# Instrumentation of the fuzz build (STRIDE_BUILD_FUZZ, clang only; toolchain/fuzz.sh and
# toolchain/fuzz-coverage.sh configure it).
#
# Included before any project target is defined, so every library a fuzz target links
# (stride_hal and whatever it pulls in) is compiled the way the targets are:
#  - fuzzing (default): -fsanitize=fuzzer-no-link,address,undefined, so libFuzzer sees the
#    edges and comparisons inside the parser, codecs and virtual buses, and ASan/UBSan check
#    their memory accesses and arithmetic; UBSan reports abort, so libFuzzer keeps the input.
#    The fuzz targets link with -fsanitize=fuzzer,address,undefined (STRIDE_FUZZ_LINK_FLAGS).
#  - STRIDE_FUZZ_COVERAGE=ON: clang source-based coverage (-fprofile-instr-generate
#    -fcoverage-mapping) and no sanitizers; the targets link libFuzzer's driver only, to run a
#    corpus once (-runs=0) for llvm-cov.
option(STRIDE_FUZZ_COVERAGE "Fuzz build with source-based coverage instead of sanitizers" OFF)

if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(WARNING "STRIDE_BUILD_FUZZ needs clang (libFuzzer); fuzz targets skipped")
  return()
endif()

if(STRIDE_FUZZ_COVERAGE)
  add_compile_options(-fprofile-instr-generate -fcoverage-mapping)
  add_link_options(-fprofile-instr-generate)
  set(STRIDE_FUZZ_LINK_FLAGS -fsanitize=fuzzer)
else()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  # Any other program of this build (not built by the fuzz scripts) still links.
  add_link_options(-fsanitize=address,undefined)
  set(STRIDE_FUZZ_LINK_FLAGS -fsanitize=fuzzer,address,undefined)
endif()
