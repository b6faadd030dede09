# Cross build for armhf (Debian armmp: Cortex-A, hard float).
set(ADVEE_ARM_TRIPLET arm-linux-gnueabihf)
include(${CMAKE_CURRENT_LIST_DIR}/arm-toolchain-common.cmake)
