#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# Every program of the install manifest follows the command-line conventions
# (docs/command-line.md): a bad option exits 2 and names the option,
# --version prints the build's version, --help exits 0. The list comes from
# docs/install.md, so a new program is checked as soon as it is installed.
# Names (docs/command-line.md "Names"): every program in /usr/bin and
# /usr/sbin of the staging install starts with "advee-", except the
# manifest's aliases, each a symlink to its program.
. "$(dirname "$0")/lib.sh"
. "$VMTEST_REPO/tests/lib/cli.sh"
trap cleanup_mounts EXIT

mapfile -t programs < <(cli_programs)
mapfile -t aliases < <(cli_aliases)
tap_plan $((2 + 3 * ${#programs[@]} + 2 * ${#aliases[@]}))
tap_here "staging install of the userland" stage_install --modules none
for p in "${programs[@]}"; do
	cli_check "$DEST" "$p"
done
for a in "${aliases[@]}"; do
	cli_check_alias "$DEST" "${a% *}" "${a#* }"
done
bad=
while read -r f; do
	case " ${aliases[*]%% *} " in *" $f "*) continue ;; esac
	cli_name_ok "$f" || bad="$bad $f"
done < <(cd "$DEST" && find usr/bin usr/sbin -mindepth 1 | sed 's|^|/|' | sort)
tap_ok "every program in /usr/bin and /usr/sbin is named advee-* (not the aliases):${bad:- all}" test -z "$bad"
tap_finish
