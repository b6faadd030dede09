#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
#
# cross-check.sh TARGET (armhf|armel): the user-space cross build for TARGET
# (scripts/build-userland.sh, which also checks the ABI of every ELF file),
# then a staging install of it with the target's modules
# (scripts/install.sh --arch TARGET) checked against the manifest of
# docs/install.md for that target: a program that a cross build leaves out
# fails here instead of vanishing from the robot's packages.
set -euo pipefail
. "$(dirname "$0")/lib.sh"

target=${1:?target (armhf|armel)}
case $target in armhf|armel) ;; *) die "cross-check.sh: unknown target $target" ;; esac
"$TOP/scripts/build-userland.sh" "$target"
[ -s "$BUILD/kmod/$target/modules.list" ] || "$TOP/scripts/build-kmod.sh" "$target"
stage=$BUILD/stage-$target
rm -rf "$stage"
"$TOP/scripts/install.sh" --destdir "$stage" --arch "$target" --modules kmod >"$stage.log" 2>&1 || {
	tail -20 "$stage.log" >&2
	die "staging install for $target failed (log: $stage.log)"
}
kver=$(ls "$stage/lib/modules")
if ! out=$("$TOP/scripts/install-manifest.sh" "$stage" "$kver" "$target"); then
	printf '%s\n' "$out" >&2
	die "the $target install does not match docs/install.md"
fi
say "$target: the staging install matches docs/install.md ($(find "$stage" -type f | wc -l) files)"
