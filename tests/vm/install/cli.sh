#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Every program of the install manifest follows the command-line conventions
# (docs/command-line.md): a bad option exits 2 and names the option,
# --version prints the build's version, --help exits 0. The list comes from
# docs/install.md, so a new program is checked as soon as it is installed.
. "$(dirname "$0")/lib.sh"
. "$VMTEST_REPO/tests/lib/cli.sh"
trap cleanup_mounts EXIT

mapfile -t programs < <(cli_programs)
tap_plan $((1 + 3 * ${#programs[@]}))
tap_here "staging install of the userland" stage_install --modules none
for p in "${programs[@]}"; do
	cli_check "$DEST" "$p"
done
tap_finish
