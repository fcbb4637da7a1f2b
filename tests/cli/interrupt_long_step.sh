#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# SIGTERM inside one long step stops the run within a second: ida-ggl on the paper's spatulas with a
# sampled trajectory restarts IDA at each of its 100 samples (about 1 s each, so the first output
# step takes a minute), and the signal is heard in IDA's callbacks, not at the step's end. The run
# says what the restarts cost before it starts, exits 143 and keeps results.incomplete.h5.
# usage: interrupt_long_step.sh ROIFEM SCENARIO_DIR WORK_DIR
set -eu
roifem=$1 scenarios=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
mesh=$(cd "$scenarios/../meshes" && pwd)/brain-800.msh
awk 'BEGIN { print "t_s,x_mm,y_mm,z_mm"; for (i = 0; i <= 100; i++) { t = 0.001 * i; printf "%.6f,%.9f,0,0\n", t, -10 * t * t } }' \
  > "$work/path.csv"
sed -e "s#^mesh = .*#mesh = \"$mesh\"#" -e "0,/^displacement_mm = .*/s##trajectory = \"$work/path.csv\"#" \
  -e '0,/^ramp_s = .*/s###' -e 's/^integrator = .*/integrator = "ida-ggl"\nrtol = 1e-6/' -e 's/^steps = .*/steps = 2/' \
  "$scenarios/paper-spatulas-setup1.toml" > "$work/sampled.toml"
"$roifem" run "$work/sampled.toml" --out "$work/out" > "$work/log.txt" 2>&1 &
pid=$!
sleep 3  # set up in 0.1 s; the first step takes about a minute
kill -TERM "$pid"
start=$(date +%s%N)
status=0
wait "$pid" || status=$?
elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
cat "$work/log.txt"
grep -q "ida-ggl restarts IDA at each of the 100 kinks of the tools' paths within the run" "$work/log.txt" ||
  { echo "the restarts' cost was not said before the run"; exit 1; }
[ "$status" -eq 143 ] || { echo "exit status $status, expected 143"; exit 1; }
[ "$elapsed_ms" -lt 1000 ] || { echo "stopped $elapsed_ms ms after SIGTERM, not within a second"; exit 1; }
grep -q "stopped: interrupted by signal 15 during step 1 of 2" "$work/log.txt" || { echo "no message naming the step"; exit 1; }
/usr/bin/python3 "$(dirname "$0")/check_results.py" "$work/out/results.incomplete.h5" "incomplete: interrupted by signal 15" 1
echo "ok: stopped ${elapsed_ms} ms after SIGTERM"
