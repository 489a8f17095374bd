# Toolchain for the igus robot's PC: Intel Core i7-5500U (Broadwell, x86-64), running an older
# Ubuntu. Builds a fully static stride-fw (no shared-library dependencies) tuned for Broadwell,
# so the binary runs whatever the robot's distribution ships.
#
#   cmake --preset igus-pc && cmake --build --preset igus-pc
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(CMAKE_C_COMPILER gcc)
set(CMAKE_CXX_COMPILER g++)

set(CMAKE_C_FLAGS_INIT "-march=broadwell -mtune=broadwell")
set(CMAKE_CXX_FLAGS_INIT "-march=broadwell -mtune=broadwell")
# Static: libstdc++, libc (glibc static works for stride-fw: it does not use NSS or dlopen) and
# libserialport (Debian ships libserialport.a).
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")
set(STRIDE_STATIC ON CACHE BOOL "Link every library statically")
