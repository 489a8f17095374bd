# Chooses the Simbody the simulator links against and whether its headers need NDEBUG.
#
# Preferred: the optimised NDEBUG build of Debian's own Simbody 3.7 source made by
# toolchain/build-simbody.sh (about 2.2x faster, bit-identical trajectories).
# Fallback: Debian's binary libsimbody-dev, which is built without NDEBUG.
#
# Simbody's headers change class layouts under NDEBUG, so code that includes them must be
# compiled with NDEBUG exactly when the library was: stride_use_simbody_headers() below.
# Simbody_DIR is set here on every configure (never trusted from an older cache), so removing
# or adding the optimised build cannot leave a build mixing headers of one with the other.

set(STRIDE_SIMBODY_PREFIX "/opt/stride/simbody-3.7"
    CACHE PATH "Prefix of the Simbody built by toolchain/build-simbody.sh")

set(_stride_simbody_stamp "${STRIDE_SIMBODY_PREFIX}/share/stride-simbody-build")
if(EXISTS "${_stride_simbody_stamp}")
  file(READ "${_stride_simbody_stamp}" _stride_simbody_build)
  string(STRIP "${_stride_simbody_build}" _stride_simbody_build)
else()
  set(_stride_simbody_build "")
endif()

if(_stride_simbody_build MATCHES " NDEBUG$")
  set(Simbody_DIR "${STRIDE_SIMBODY_PREFIX}/lib/cmake/simbody" CACHE PATH "" FORCE)
  find_package(Simbody REQUIRED CONFIG NO_DEFAULT_PATH PATHS "${Simbody_DIR}")
  set(STRIDE_SIMBODY_NDEBUG ON)
  message(STATUS "Simbody: ${_stride_simbody_build} in ${STRIDE_SIMBODY_PREFIX}")
else()
  if(DEFINED CACHE{Simbody_DIR} AND Simbody_DIR MATCHES "^${STRIDE_SIMBODY_PREFIX}")
    unset(Simbody_DIR CACHE)
  endif()
  find_package(Simbody REQUIRED)
  set(STRIDE_SIMBODY_NDEBUG OFF)
  message(STATUS "Simbody: Debian's libsimbody in ${Simbody_DIR}, built without NDEBUG and "
                 "about 2.2x slower; toolchain/build-simbody.sh builds the faster one")
endif()

if(STRIDE_SIMBODY_NDEBUG AND NOT Simbody_INCLUDE_DIR MATCHES "^${STRIDE_SIMBODY_PREFIX}")
  message(FATAL_ERROR "Simbody headers (${Simbody_INCLUDE_DIR}) are not the optimised build's "
                      "in ${STRIDE_SIMBODY_PREFIX}; delete the build directory and configure again")
endif()

# Compiles `target`'s sources against Simbody's headers the one safe way: its include
# directory as a system directory, and NDEBUG exactly when the library was built with it.
function(stride_use_simbody_headers target)
  target_include_directories(${target} SYSTEM PRIVATE ${Simbody_INCLUDE_DIR})
  if(STRIDE_SIMBODY_NDEBUG)
    # GCC 12 -O3 reports a false array-bounds warning inside Simbody's Mat/Vec headers (a
    # Mat33 row viewed as a strided Vec3) once their NDEBUG paths are inlined.
    target_compile_options(${target} PRIVATE -DNDEBUG -Wno-array-bounds)
  else()
    target_compile_options(${target} PRIVATE -UNDEBUG)
  endif()
endfunction()
