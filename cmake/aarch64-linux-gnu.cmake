# Cross-compiling raps for 64-bit ARM Linux with Debian's cross compiler, to check that the
# output has the same bits as on x86-64 (docs/reproducibility.md, "Across architectures"):
#   apt-get install g++-aarch64-linux-gnu qemu-user-static
#   cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
#         -DBUILD_SHARED_LIBS=OFF -DRAPS_BUILD_TESTS=OFF -DRAPS_BUILD_BENCH=OFF -DRAPS_BUILD_GLTF=OFF
#   cmake --build build-aarch64 --target raps-param
# The executables run under qemu-user (CMAKE_CROSSCOMPILING_EMULATOR below).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
# Eigen is headers only: the host's package (libeigen3-dev) serves the target too.
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64-static -L /usr/aarch64-linux-gnu)
