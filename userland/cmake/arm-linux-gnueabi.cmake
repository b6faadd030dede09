# Cross build for armel (Debian marvell: the TS-7800's ARMv5TE Feroceon, soft float).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-linux-gnueabi-gcc)
set(CMAKE_CXX_COMPILER arm-linux-gnueabi-g++)
set(CMAKE_FIND_ROOT_PATH /usr/arm-linux-gnueabi)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Debian's arm-linux-gnueabi builds of the libraries (scripts/fetch-arm-sysroot.sh, passed
# by scripts/build-userland.sh as ADVEE_ARM_SYSROOT): searched after the
# toolchain's own root; pkg-config reads only their .pc files and prefixes
# their paths with the sysroot; the linker resolves their DT_NEEDED there.
if(ADVEE_ARM_SYSROOT)
  set(CMAKE_LIBRARY_ARCHITECTURE arm-linux-gnueabi)
  list(APPEND CMAKE_FIND_ROOT_PATH ${ADVEE_ARM_SYSROOT})
  set(ENV{PKG_CONFIG_SYSROOT_DIR} ${ADVEE_ARM_SYSROOT})
  set(ENV{PKG_CONFIG_LIBDIR} "${ADVEE_ARM_SYSROOT}/usr/lib/arm-linux-gnueabi/pkgconfig:${ADVEE_ARM_SYSROOT}/usr/share/pkgconfig")
  set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-Wl,-rpath-link,${ADVEE_ARM_SYSROOT}/usr/lib/arm-linux-gnueabi -Wl,-rpath-link,${ADVEE_ARM_SYSROOT}/lib/arm-linux-gnueabi")
  set(CMAKE_SHARED_LINKER_FLAGS_INIT "${CMAKE_EXE_LINKER_FLAGS_INIT}")
endif()
