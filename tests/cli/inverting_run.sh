#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A neo-Hookean run whose element inverts stops naming the method, the step, the time and the
# tetrahedron (exit 1), keeps its good steps in results.incomplete.h5 and leaves the good
# results.h5 of an earlier run in the same directory byte for byte as it was. The spatulas of the
# paper's setup 1 pull the opening's walls 30 mm apart in 0.5 s: the tissue under them inverts.
# usage: inverting_run.sh ROIFEM SCENARIO_DIR WORK_DIR INTEGRATOR [RTOL]
set -eu
roifem=$1 scenarios=$2 work=$3 integrator=$4 rtol=${5:-}
rm -rf "$work"
mkdir -p "$work"
mesh=$(cd "$scenarios/../meshes" && pwd)/brain-800.msh
sed -e "s#^mesh = .*#mesh = \"$mesh\"#" -e 's/^steps = .*/steps = 5/' "$scenarios/paper-setup2.toml" > "$work/good.toml"
"$roifem" run "$work/good.toml" --out "$work" > "$work/good-log.txt" 2>&1
good=$(md5sum < "$work/results.h5")
sed -e "s#^mesh = .*#mesh = \"$mesh\"#" -e "s/^integrator = .*/integrator = \"$integrator\"/" -e 's/^steps = .*/steps = 20/' \
  -e 's/^displacement_mm = \[-1.0/displacement_mm = [-30.0/' -e 's/^displacement_mm = \[1.0/displacement_mm = [30.0/' \
  "$scenarios/paper-spatulas-setup1-neo-hookean.toml" > "$work/inverting.toml"
[ -n "$rtol" ] && sed -i "s/^steps = 20$/steps = 20\nrtol = $rtol/" "$work/inverting.toml"
status=0
"$roifem" run "$work/inverting.toml" --out "$work" > "$work/log.txt" 2>&1 || status=$?
tail -n 3 "$work/log.txt"
[ "$status" -eq 1 ] || { echo "exit status $status, expected 1"; exit 1; }
grep -qE "error: $integrator: (failed at )?step [0-9]+, (after )?t = [0-9.e-]+ s: .*tetrahedron [0-9]+ \(nodes [0-9 ]+\) has inverted" "$work/log.txt" ||
  { echo "message does not name the method, the step, t and the tetrahedron"; exit 1; }
[ "$(md5sum < "$work/results.h5")" = "$good" ] || { echo "the failed run replaced the good results.h5"; exit 1; }
/usr/bin/python3 "$(dirname "$0")/check_results.py" "$work/results.incomplete.h5" "incomplete: $integrator: " 0
echo "ok: inverted, named, the earlier result untouched"
