# SPDX-License-Identifier: GPL-2.0
# candump.sh - a candump of a CAN interface that has seen everything a test
# sent (source it; bash). Ready and complete are conditions, not sleeps: a
# marker frame with a 29-bit id (which never matches a CANopen COB-ID, so
# no node reacts to it: userland/canopen/src/socketcan.cpp) is sent until
# candump has logged it; candump_stop leaves the markers out of the log.
#   candump_start IF FILE   candump -L of IF into FILE, receiving when it returns
#   candump_sync            every frame sent before it is in FILE
#   candump_stop            candump_sync, candump ended, markers removed
. "$VMTEST_REPO/tests/lib/wait.sh"

CANDUMP_MARK=1FFFFFFF
CANDUMP_PID=
CANDUMP_IF=
CANDUMP_FILE=
CANDUMP_SEQ=0

# _candump_mark: true once candump logged marker CANDUMP_SEQ; else send it (again).
_candump_mark() {
	local m
	m=$CANDUMP_MARK#$(printf '%08X' "$CANDUMP_SEQ")
	grep -q " $m\$" "$CANDUMP_FILE" 2>/dev/null && return 0
	cansend "$CANDUMP_IF" "$m"
	return 1
}

candump_sync() {
	CANDUMP_SEQ=$((CANDUMP_SEQ + 1))
	wait_until 10 _candump_mark && return 0
	echo "# candump on $CANDUMP_IF did not log marker $CANDUMP_SEQ within 10 s"
	return 1
}

candump_start() {
	CANDUMP_IF=$1 CANDUMP_FILE=$2
	candump -L "$CANDUMP_IF" >"$CANDUMP_FILE" 2>&1 &
	CANDUMP_PID=$!
	candump_sync
}

candump_stop() {
	candump_sync
	kill "$CANDUMP_PID" 2>/dev/null
	wait "$CANDUMP_PID" 2>/dev/null
	CANDUMP_PID=
	sed -i "/ $CANDUMP_MARK#/d" "$CANDUMP_FILE"
}
