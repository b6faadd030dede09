#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Runs bench/daemons.sh armel (the TS-7800's cross-built binaries under
# qemu-user) in the VM and shows its table as diagnostics; what could not run
# under qemu-user is listed with the reason. Needs build/userland-armel
# (scripts/build-userland.sh armel) and qemu-user.
. "$VMTEST_REPO/tests/lib/tap.sh"
SUITE_DIR=$(dirname "$0")
. "$SUITE_DIR/bench-common.inc"
bench_daemons armel
