# SPDX-License-Identifier: GPL-2.0
#
# Advee low-level stack: the one entry point.
#
#   make                 kernel modules (amd64, W=1) + userland + VM test programs
#   make ARCH=arm        cross-build modules for armhf (armmp) and armel (marvell),
#                        userland and static test programs for both
#   make check           everything the README's test command runs (see docs/testing.md)
#   make check-fast      gates, unit tests, kernel suites on the x86_64 lane (iteration)
#   make check TEST=name one VM test (suite or suite/program) on the x86_64 lane
#   make demo            the main job: the robot's low level on the simulated
#                        robot in the VM, advee-diagnostic-center on this terminal
#                        (FOR=30s: non-interactive, a text summary every 5 s)
#   make deps            install what this machine lacks (idempotent)
#   make gates           W=1 + checkpatch --strict + sparse on the kernel sources
#   make unit            CTest in the ASan/UBSan build (VARIANTS="native asan": both)
#   make vm-x86 / vm-arm / vm-debug  one VM lane (vm-debug: KASAN/lockdep kernel)
#   make bench           the benchmarks: VM programs named bench* (TEST= selects)
#   make fuzz            the fuzz programs at the goal's sizes on the debug kernel
#   make install         install the built stack (DESTDIR= stages it; ARCH=arm
#                        TARGET=armel|armhf the ARM build; MODULES=dkms|none)
#   make dkms-source     the module sources into $(DESTDIR)/usr/src/advee-VERSION
#   make debs            the Debian packages into build/debs/, lintian-checked
#                        (ARCH=arm [TARGET=armel|armhf]: cross-built for the
#                        robot into build/debs-armel/, build/debs-armhf/)
#   make clean
#
# KDIR=... builds the modules against another kernel tree (default: Debian's
# newest installed 6.1 amd64 headers). V=1 shows full commands.

SHELL := /bin/bash
TOP := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
BUILD := $(TOP)/build

# The kernel release the x86_64 VM boots and the modules are built for.
KVER ?= $(shell $(TOP)/scripts/kver.sh)
KDIR ?= /usr/src/linux-headers-$(KVER)

# Sources that make up the Kbuild tree (copied per target, see build-kmod.sh).
KSRC_DIRS := kernel tsuart-fix rs485proto i2c-max6615 tests/kmod tests/sim ts7800-can

TEST ?=
export KVER KDIR TOP BUILD

.PHONY: debs all default modules userland testprogs arm arm-modules arm-userland arm-testprogs \
	check check-fast unit gates vm-x86 vm-arm vm-debug bench fuzz demo deps clean help \
	install dkms-source

ifeq ($(ARCH),arm)
default: arm
else
default: all
endif

all: modules userland testprogs

help:
	@sed -n '3,27p' $(TOP)/Makefile | sed 's/^# \{0,1\}//'

deps:
	@$(TOP)/scripts/deps.sh

# Kernel modules ------------------------------------------------------------
modules:
	@$(TOP)/scripts/build-kmod.sh $(if $(filter /usr/src/linux-headers-$(KVER),$(KDIR)),x86_64,custom) "$(KDIR)"

# ARCH=arm is also in the environment of the sub-makes; the scripts set what
# each target needs explicitly.
arm: arm-modules arm-userland arm-testprogs

arm-modules:
	@$(TOP)/scripts/build-kmod.sh armhf
	@$(TOP)/scripts/build-kmod.sh armel

# User space ------------------------------------------------------------------
userland:
	@$(TOP)/scripts/build-userland.sh native

arm-userland:
	@$(TOP)/scripts/build-userland.sh armhf
	@$(TOP)/scripts/build-userland.sh armel

# VM test programs (tests/vm/<suite>/*.c) --------------------------------------
testprogs:
	@$(TOP)/scripts/build-testprogs.sh x86_64

arm-testprogs:
	@$(TOP)/scripts/build-testprogs.sh armhf

# Tests -----------------------------------------------------------------------
check:
	@$(TOP)/scripts/check.sh $(if $(TEST),--test "$(TEST)")

check-fast:
	@$(TOP)/scripts/check.sh --fast

unit:
	@$(TOP)/scripts/unit.sh $(VARIANTS)

gates:
	@$(TOP)/scripts/kernel-gates.sh

vm-x86: modules testprogs userland
	@$(TOP)/tests/harness/vm-x86.sh $(if $(TEST),--test "$(TEST)")

vm-arm:
	@$(TOP)/scripts/build-kmod.sh armhf
	@$(TOP)/scripts/build-testprogs.sh armhf
	@$(TOP)/tests/harness/vm-arm.sh $(if $(TEST),--test "$(TEST)")

vm-debug:
	@$(TOP)/tests/harness/vm-debug.sh $(if $(TEST),--test "$(TEST)")

bench: modules testprogs userland
	@VMTEST_BENCH=1 $(TOP)/tests/harness/vm-x86.sh --lane bench $(if $(TEST),--test "$(TEST)")

# The fuzz programs at the goal's sizes of issue 26 (ADVEE_FUZZ_SCALE=full:
# 100,000 ioctls on the discipline and on the wires, 10^6 wire characters,
# 5,000 and 10,000 sysfs writes) on the debug kernel, lane fuzz; make check
# runs the same programs at the ci sizes (docs/testing.md). TEST= selects.
FUZZ_PROGRAMS := rs485proto/fuzz rs485proto/ioctlfuzz max6615/sysfs-fuzz dio-i2c/sysfs-fuzz
fuzz:
	@ADVEE_FUZZ_SCALE=full $(TOP)/tests/harness/vm-debug.sh --lane fuzz \
		$(foreach t,$(or $(TEST),$(FUZZ_PROGRAMS)),--test $(t))

# Installation (docs/install.md) ------------------------------------------------
install:
	@$(TOP)/scripts/install.sh $(if $(DESTDIR),--destdir "$(DESTDIR)") \
		$(if $(filter arm,$(ARCH)),--arch $(or $(TARGET),armel)) $(if $(MODULES),--modules $(MODULES))

dkms-source:
	@$(TOP)/scripts/install.sh --dkms-source-only $(if $(DESTDIR),--destdir "$(DESTDIR)")

debs:
	@$(TOP)/scripts/build-debs.sh --lintian $(if $(filter arm,$(ARCH)),--arch $(or $(TARGET),armel))

demo:
	@$(TOP)/scripts/demo.sh $(if $(FOR),--for "$(FOR)")

clean:
	rm -rf $(BUILD)
