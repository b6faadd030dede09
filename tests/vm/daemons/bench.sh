#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Runs bench/daemons.sh (x86_64: the native build) in the VM and shows its
# table as diagnostics. The test points check only that the measurement ran
# and that the modules ran at their rates; memory and CPU are never asserted.
. "$VMTEST_REPO/tests/lib/tap.sh"
SUITE_DIR=$(dirname "$0")
. "$SUITE_DIR/bench-common.inc"
bench_daemons x86_64
