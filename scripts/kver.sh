#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0
# Print the release of Debian's newest installed 6.1 amd64 kernel that also has
# headers: the kernel the x86_64 VM lane boots and the modules are built for.
set -euo pipefail
for d in $(ls -d /usr/src/linux-headers-6.1.*-amd64 2>/dev/null | sort -V -r); do
	rel=${d#/usr/src/linux-headers-}
	if [ -e "/boot/vmlinuz-$rel" ] && [ -d "/lib/modules/$rel" ]; then
		echo "$rel"
		exit 0
	fi
done
echo "kver.sh: no Debian 6.1 amd64 kernel with headers installed (run: make deps)" >&2
echo none
