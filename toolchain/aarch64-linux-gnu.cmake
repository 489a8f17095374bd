# Cross toolchain for 64-bit ARM Linux (aarch64) with Debian's cross compiler and the arm64
# multiarch libraries (toolchain/install-deps.sh --cross installs both, plus qemu-user).
# Tests run under qemu user-mode emulation through CMAKE_CROSSCOMPILING_EMULATOR.
#
#   cmake --preset aarch64 && cmake --build --preset aarch64 && ctest --preset aarch64
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

# Headers and architecture-independent CMake packages (Eigen, nlohmann-json) come from /usr;
# libraries only from the arm64 multiarch folders.
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu /usr)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
set(ENV{PKG_CONFIG_LIBDIR} "/usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig")

# The emulated programs load the arm64 multiarch runtime (libc6:arm64, libstdc++6:arm64 in
# /lib/aarch64-linux-gnu), not the cross toolchain's private copy in /usr/aarch64-linux-gnu:
# with that older copy, qemu-user 7.2 hangs in the first pthread join.
find_program(STRIDE_QEMU_AARCH64 NAMES qemu-aarch64 qemu-aarch64-static)
if(STRIDE_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${STRIDE_QEMU_AARCH64};-L;/")
endif()
