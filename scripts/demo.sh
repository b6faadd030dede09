#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# demo.sh: the main job (README, first command). Installs what is missing,
# builds the project's modules and boots the x86_64 VM with them: the guest
# loads every module, prints what it registered and unloads it again. Later
# issues turn this into the whole stack running on the simulated robot.
set -euo pipefail
. "$(dirname "$0")/lib.sh"
"$TOP/scripts/deps.sh"
"$TOP/scripts/build-kmod.sh" x86_64
exec "$TOP/tests/harness/vm-x86.sh" --lane demo --run "$TOP/tests/harness/demo-guest.sh"
