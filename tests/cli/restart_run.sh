#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A restarted run against the run that never stopped: SCENARIO (a shipped one) run for STEPS steps,
# and for STEPS - 10, then `roifem run --from` the shorter run's last step for STEPS. exact: every
# dataset of the two results.h5 bit-identical (wall times apart); afresh: steps 0..K identical and
# the difference after them printed (the library methods start afresh from u and v).
# usage: restart_run.sh ROIFEM SCENARIO_DIR WORK SCENARIO INTEGRATOR STEPS exact|afresh [RTOL]
set -eu
roifem=$1 scenarios=$2 work=$3 scenario=$4 integrator=$5 steps=$6 mode=$7 rtol=${8:-}
here=$(dirname "$0")
rm -rf "$work"
mkdir -p "$work"
make() {  # make NAME STEPS
  sed -e "s#\.\./meshes/#$(cd "$scenarios/../meshes" && pwd)/#" -e "s/^integrator = .*/integrator = \"$integrator\"/" \
      -e "s/^steps = .*/steps = $2/" -e "s/^field_every = .*/field_every = 10\nrestart_every = 10/" "$scenarios/$scenario.toml" > "$work/$1.toml"
  [ -z "$rtol" ] || sed -i "s/^steps = $2\$/steps = $2\nrtol = $rtol/" "$work/$1.toml"
}
make long "$steps"
make short $((steps - 10))
"$roifem" run "$work/long.toml" --out "$work/unbroken" > "$work/unbroken.log" 2>&1
"$roifem" run "$work/short.toml" --out "$work/short" > "$work/short.log" 2>&1
"$roifem" run "$work/long.toml" --out "$work/restarted" --from "$work/short/results.h5" > "$work/restarted.log" 2>&1 ||
  { cat "$work/restarted.log"; exit 1; }
grep "restarted from" "$work/restarted.log"
if [ "$mode" = exact ]; then
  grep -q "goes on exactly" "$work/restarted.log" || { echo "the restart does not say it goes on exactly"; exit 1; }
  /usr/bin/python3 "$here/same_results.py" "$work/unbroken/results.h5" "$work/restarted/results.h5"
  echo "ok: $integrator restarted at step $((steps - 10)), bit for bit"
else
  grep -q "starts afresh from u, v" "$work/restarted.log" || { echo "the restart does not say it starts afresh"; exit 1; }
  /usr/bin/python3 "$here/restart_difference.py" "$work/unbroken/results.h5" "$work/restarted/results.h5" $((steps - 10))
  echo "ok: $integrator restarted afresh at step $((steps - 10))"
fi
