# Cross build for armel (Debian marvell: the TS-7800's ARMv5TE Feroceon, soft float).
set(ADVEE_ARM_TRIPLET arm-linux-gnueabi)
include(${CMAKE_CURRENT_LIST_DIR}/arm-toolchain-common.cmake)
