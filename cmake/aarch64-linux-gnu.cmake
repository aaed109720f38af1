# Cross-compiling for 64-bit ARM Linux (Raspberry Pi 3/4/5 with a 64-bit OS) with Debian's
# crossbuild-essential-arm64 and the :arm64 multiarch -dev packages (scripts/install_arm64_deps.sh).
# Programs built with it run on this machine under qemu-user: CTest and gtest_discover_tests start
# them through the emulator below.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# Multiarch: the arm64 libraries and their CMake files live in /usr/lib/aarch64-linux-gnu, not in a
# sysroot; headers are shared with the host in /usr/include.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)
# yaml-cpp's arm64 -dev package is not co-installable with the host's; see the file here.
set(yaml-cpp_DIR "${CMAKE_CURRENT_LIST_DIR}/aarch64-linux-gnu" CACHE PATH "yaml-cpp for arm64")
