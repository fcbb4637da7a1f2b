#!/bin/sh
# An explicit method past its stability limit stops naming the method, t and step, and keeps every
# good step before the divergence in results.incomplete.h5 (nothing non-finite in it).
# usage: diverging_run.sh ROIFEM SCENARIO_DIR WORK_DIR
set -eu
roifem=$1 scenarios=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
mesh=$(cd "$scenarios/../meshes" && pwd)/brain-800.msh
# arkode-erk4 is stable up to dt = 1.3e-3 s on setup 2 (w_max ~ 2150 rad/s); run it at 2e-3 s.
sed -e "s#^mesh = .*#mesh = \"$mesh\"#" -e 's/^integrator = .*/integrator = "arkode-erk4"/' -e 's/^dt_s = .*/dt_s = 0.002/' \
  -e 's/^steps = .*/steps = 5000/' "$scenarios/paper-setup2.toml" > "$work/unstable.toml"
status=0
"$roifem" run "$work/unstable.toml" --out "$work" > "$work/log.txt" 2>&1 || status=$?
tail -n 3 "$work/log.txt"
[ "$status" -eq 1 ] || { echo "exit status $status, expected 1"; exit 1; }
grep -qE "arkode-erk4: the solution diverged .* by t = [0-9.]+ s, step [0-9]+" "$work/log.txt" || { echo "message does not name method, t and step"; exit 1; }
[ ! -e "$work/results.h5" ] || { echo "a failed run wrote results.h5"; exit 1; }
/usr/bin/python3 "$(dirname "$0")/check_results.py" "$work/results.incomplete.h5" "incomplete: arkode-erk4: the solution diverged" 5
echo "ok: diverged, good steps kept"
