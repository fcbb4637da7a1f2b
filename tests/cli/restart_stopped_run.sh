#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A long run stopped by Ctrl-C goes on from its results.incomplete.h5: SIGINT 1 s into its steps, then
# `roifem run --from` its last restart point for 20 steps more, against a run of as many steps
# that never stopped (every dataset bit-identical, wall times apart).
# usage: restart_stopped_run.sh ROIFEM SCENARIO_DIR WORK_DIR
set -eu
roifem=$1 scenarios=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
mesh=$(cd "$scenarios/../meshes" && pwd)/brain-800.msh
scenario() { sed -e "s/^steps = .*/steps = $1/" -e "s#^mesh = .*#mesh = \"$mesh\"#" "$scenarios/paper-setup2.toml"; }
scenario 1000000 > "$work/long.toml"
"$roifem" run "$work/long.toml" --out "$work/stopped" > "$work/stopped.log" 2>&1 &
pid=$!
# SIGINT once the run is under way: a background job of a script starts with SIGINT ignored (POSIX),
# so a signal sent before the run installs its handler is lost (under the sanitizers, on a loaded
# machine, setting up took over the 1 s this test once waited, and the run went on for its million steps).
# Under way: its results file (a temporary name until the run ends) is there.
for _ in $(seq 600); do [ -n "$(ls -A "$work/stopped" 2>/dev/null)" ] && break; sleep 0.1; done
sleep 1
kill -INT "$pid"
wait "$pid" || true
last=$(/usr/bin/python3 -c "
import h5py, sys
with h5py.File(sys.argv[1], 'r') as f: print(max(int(k[5:]) for k in f['restart']))" "$work/stopped/results.incomplete.h5")
echo "stopped; its last restart point: step $last"
scenario $((last + 20)) > "$work/more.toml"
"$roifem" run "$work/more.toml" --out "$work/unbroken" > "$work/unbroken.log" 2>&1
"$roifem" run "$work/more.toml" --out "$work/restarted" --from "$work/stopped/results.incomplete.h5" > "$work/restarted.log" 2>&1 ||
  { cat "$work/restarted.log"; exit 1; }
grep "restarted from" "$work/restarted.log"
/usr/bin/python3 "$(dirname "$0")/same_results.py" "$work/unbroken/results.h5" "$work/restarted/results.h5"
echo "ok: the stopped run went on from step $last, bit for bit"
