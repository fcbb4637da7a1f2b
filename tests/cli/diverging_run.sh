#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A method past its stability limit stops naming the method, t and step (exit 1), keeps every good
# step before the divergence in results.incomplete.h5 (nothing non-finite in it), and leaves the
# good results.h5 of an earlier run in the same directory byte for byte as it was.
# usage: diverging_run.sh ROIFEM SCENARIO_DIR WORK_DIR INTEGRATOR DT_S STEPS MIN_KEPT_STEPS
set -eu
roifem=$1 scenarios=$2 work=$3 integrator=$4 dt=$5 steps=$6 kept=$7
rm -rf "$work"
mkdir -p "$work"
mesh=$(cd "$scenarios/../meshes" && pwd)/brain-800.msh
sed -e "s#^mesh = .*#mesh = \"$mesh\"#" -e 's/^steps = .*/steps = 20/' "$scenarios/paper-setup2.toml" > "$work/good.toml"
"$roifem" run "$work/good.toml" --out "$work" > "$work/good-log.txt" 2>&1
good=$(md5sum < "$work/results.h5")
sed -e "s#^mesh = .*#mesh = \"$mesh\"#" -e "s/^integrator = .*/integrator = \"$integrator\"/" -e "s/^dt_s = .*/dt_s = $dt/" \
  -e "s/^steps = .*/steps = $steps/" "$scenarios/paper-setup2.toml" > "$work/unstable.toml"
status=0
"$roifem" run "$work/unstable.toml" --out "$work" > "$work/log.txt" 2>&1 || status=$?
tail -n 3 "$work/log.txt"
[ "$status" -eq 1 ] || { echo "exit status $status, expected 1"; exit 1; }
grep -qE "$integrator: the solution diverged \(.*\) by t = [0-9.]+ s, step [0-9]+" "$work/log.txt" ||
  { echo "message does not name method, t and step"; exit 1; }
[ "$(md5sum < "$work/results.h5")" = "$good" ] || { echo "the failed run replaced the good results.h5"; exit 1; }
/usr/bin/python3 "$(dirname "$0")/check_results.py" "$work/results.incomplete.h5" "incomplete: $integrator: the solution diverged" "$kept"
echo "ok: diverged, good steps kept, the earlier result untouched"
