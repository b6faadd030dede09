# Shared body of the ARM toolchain files: they set ADVEE_ARM_TRIPLET and
# include this.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER ${ADVEE_ARM_TRIPLET}-gcc)
set(CMAKE_CXX_COMPILER ${ADVEE_ARM_TRIPLET}-g++)
set(CMAKE_FIND_ROOT_PATH /usr/${ADVEE_ARM_TRIPLET})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# Installed as Debian lays out the target: libraries in the multiarch
# directory (GNUInstallDirs cannot tell it from a cross compiler).
set(CMAKE_INSTALL_LIBDIR lib/${ADVEE_ARM_TRIPLET} CACHE PATH "object code libraries (multiarch)")

# Debian's ${ADVEE_ARM_TRIPLET} builds of the libraries (scripts/fetch-arm-sysroot.sh, passed
# by scripts/build-userland.sh as ADVEE_ARM_SYSROOT): searched after the
# toolchain's own root; pkg-config reads only their .pc files and prefixes
# their paths with the sysroot; the linker resolves their DT_NEEDED there,
# and finds there the libraries that Debian's linker scripts name
# (libncurses.so is "INPUT(libncurses.so.6 -ltinfo)").
if(ADVEE_ARM_SYSROOT)
  set(CMAKE_LIBRARY_ARCHITECTURE ${ADVEE_ARM_TRIPLET})
  list(APPEND CMAKE_FIND_ROOT_PATH ${ADVEE_ARM_SYSROOT})
  set(ENV{PKG_CONFIG_SYSROOT_DIR} ${ADVEE_ARM_SYSROOT})
  set(ENV{PKG_CONFIG_LIBDIR} "${ADVEE_ARM_SYSROOT}/usr/lib/${ADVEE_ARM_TRIPLET}/pkgconfig:${ADVEE_ARM_SYSROOT}/usr/share/pkgconfig")
  set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-Wl,-rpath-link,${ADVEE_ARM_SYSROOT}/usr/lib/${ADVEE_ARM_TRIPLET} -Wl,-rpath-link,${ADVEE_ARM_SYSROOT}/lib/${ADVEE_ARM_TRIPLET} -L${ADVEE_ARM_SYSROOT}/usr/lib/${ADVEE_ARM_TRIPLET} -L${ADVEE_ARM_SYSROOT}/lib/${ADVEE_ARM_TRIPLET}")
  set(CMAKE_SHARED_LINKER_FLAGS_INIT "${CMAKE_EXE_LINKER_FLAGS_INIT}")
  # Debian puts a library's architecture-dependent headers under
  # /usr/include/TRIPLET (OpenSSL's openssl/opensslconf.h and
  # configuration.h), which a native gcc searches by itself and the cross
  # gcc, knowing nothing of this sysroot, does not. Last on the path: the
  # sysroot holds no libc headers, so nothing there shadows the toolchain's.
  set(CMAKE_C_STANDARD_INCLUDE_DIRECTORIES ${ADVEE_ARM_SYSROOT}/usr/include/${ADVEE_ARM_TRIPLET})
  set(CMAKE_CXX_STANDARD_INCLUDE_DIRECTORIES ${ADVEE_ARM_SYSROOT}/usr/include/${ADVEE_ARM_TRIPLET})
endif()
