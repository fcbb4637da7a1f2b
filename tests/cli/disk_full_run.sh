#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A run whose results cannot be written (a file-size limit standing in for a full disk) stops with
# a message naming the file, exit code 1, no crash, and leaves an earlier results.h5 untouched
# and no temporary file behind.
# usage: disk_full_run.sh ROIFEM SCENARIO_DIR WORK_DIR
set -u
roifem=$1 scenarios=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
echo "a good result from an earlier run" > "$work/results.h5"
status=0
# SIGXFSZ ignored, so that writes past the limit fail with EFBIG instead of killing the process.
(trap '' XFSZ; ulimit -f 200; exec "$roifem" run "$scenarios/paper-setup2.toml" --out "$work") > "$work/log.txt" 2>&1 || status=$?
cat "$work/log.txt"
[ "$status" -eq 1 ] || { echo "exit status $status, expected 1"; exit 1; }
grep -qE "results\.partial-[0-9]+\.h5: cannot (flush|write|close|create)" "$work/log.txt" || { echo "message does not name the file"; exit 1; }
[ "$(cat "$work/results.h5")" = "a good result from an earlier run" ] || { echo "results.h5 was replaced"; exit 1; }
if ls -A "$work" | grep -q partial; then echo "a temporary file was left behind"; exit 1; fi
echo "ok: disk full, nothing lost"
