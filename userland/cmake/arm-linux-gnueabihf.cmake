# Cross build for armhf (Debian armmp: Cortex-A, hard float).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-linux-gnueabihf-gcc)
set(CMAKE_CXX_COMPILER arm-linux-gnueabihf-g++)
set(CMAKE_FIND_ROOT_PATH /usr/arm-linux-gnueabihf)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Debian's arm-linux-gnueabihf builds of the libraries (scripts/fetch-arm-sysroot.sh, passed
# by scripts/build-userland.sh as ADVEE_ARM_SYSROOT): searched after the
# toolchain's own root; pkg-config reads only their .pc files and prefixes
# their paths with the sysroot; the linker resolves their DT_NEEDED there.
if(ADVEE_ARM_SYSROOT)
  set(CMAKE_LIBRARY_ARCHITECTURE arm-linux-gnueabihf)
  list(APPEND CMAKE_FIND_ROOT_PATH ${ADVEE_ARM_SYSROOT})
  set(ENV{PKG_CONFIG_SYSROOT_DIR} ${ADVEE_ARM_SYSROOT})
  set(ENV{PKG_CONFIG_LIBDIR} "${ADVEE_ARM_SYSROOT}/usr/lib/arm-linux-gnueabihf/pkgconfig:${ADVEE_ARM_SYSROOT}/usr/share/pkgconfig")
  set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-Wl,-rpath-link,${ADVEE_ARM_SYSROOT}/usr/lib/arm-linux-gnueabihf -Wl,-rpath-link,${ADVEE_ARM_SYSROOT}/lib/arm-linux-gnueabihf")
  set(CMAKE_SHARED_LINKER_FLAGS_INIT "${CMAKE_EXE_LINKER_FLAGS_INIT}")
endif()
