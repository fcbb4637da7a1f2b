#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A long `roifem run` stopped by a signal keeps what it computed and loses nothing else.
# usage: interrupt_run.sh ROIFEM SCENARIO_DIR WORK_DIR SIGNAL   (SIGNAL: INT, TERM or KILL)
#   INT / TERM: exit code 128 + signal, results.incomplete.h5 valid and marked incomplete,
#               a results.h5 already there untouched, no temporary file left.
#   KILL:       the temporary results file holds every step flushed before the kill, readable.
set -eu
roifem=$1 scenarios=$2 work=$3 signal=$4
rm -rf "$work"
mkdir -p "$work"
mesh=$(cd "$scenarios/../meshes" && pwd)/brain-800.msh
sed -e 's/^steps = .*/steps = 2000000/' -e "s#^mesh = .*#mesh = \"$mesh\"#" "$scenarios/paper-setup2.toml" > "$work/long.toml"
echo "a good result from an earlier run" > "$work/results.h5"
"$roifem" run "$work/long.toml" --out "$work" > "$work/log.txt" 2>&1 &
pid=$!
# Signal at a random point 2 to 5 s in (setup takes well under 1 s; the run flushes every 50 steps).
sleep "$(awk 'BEGIN { srand(); printf "%.2f", 2 + 3 * rand() }')"
kill -s "$signal" "$pid"
status=0
wait "$pid" || status=$?
cat "$work/log.txt" | tail -n 4
check="/usr/bin/python3 $(dirname "$0")/check_results.py"
case $signal in
  INT) expected=130 ;;
  TERM) expected=143 ;;
  KILL) expected=137 ;;
esac
[ "$status" -eq "$expected" ] || { echo "exit status $status, expected $expected"; exit 1; }
[ "$(cat "$work/results.h5")" = "a good result from an earlier run" ] || { echo "results.h5 was replaced"; exit 1; }
if [ "$signal" = KILL ]; then
  partial=$(ls "$work"/.results.partial-*.h5)
  $check "$partial" - 50
else
  $check "$work/results.incomplete.h5" "incomplete: interrupted by signal" 50
  if ls "$work"/.results.partial-* > /dev/null 2>&1; then echo "a temporary file was left behind"; exit 1; fi
fi
echo "ok: nothing lost"
