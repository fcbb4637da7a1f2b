#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# `mpirun -n 2 roifem-mpi run` writes roifem run's results: the same displacement fields as the
# serial full model to 1e-8 (CG + GAMG at rtol 1e-10), a complete status, an XDMF beside them;
# and a failing run (an unwritable --out) stops every rank with a message and leaves no file. A
# refusal every rank agrees on (a scenario with tools, to run and to condense; a misspelt PETSc
# option) is printed once, names its cause, and leaves no file and no MPI_ABORT; SIGTERM to mpirun
# stops every rank after the same step and keeps every step in results.incomplete.h5.
# usage: mpi_run.sh MPIEXEC ROIFEM_MPI ROIFEM SCENARIO_DIR WORK_DIR
set -eu
mpiexec=$1 roifem_mpi=$2 roifem=$3 scenarios=$4 work=$5
rm -rf "$work"
mkdir -p "$work"
"$mpiexec" -n 2 "$roifem_mpi" run "$scenarios/paper-full.toml" --out "$work/mpi" -- -ksp_type cg -pc_type gamg -ksp_rtol 1e-10 \
  > "$work/mpi.log" 2>&1 || { cat "$work/mpi.log"; exit 1; }
cat "$work/mpi.log"
grep -q "2052 dofs on 2 ranks" "$work/mpi.log"
"$roifem" run "$scenarios/paper-full.toml" --out "$work/serial" > "$work/serial.log"
test -f "$work/mpi/results.xdmf"
/usr/bin/python3 - "$work/mpi/results.h5" "$work/serial/results.h5" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1], "r") as a, h5py.File(sys.argv[2], "r") as b:
    status = a.attrs["status"]
    status = status.decode() if isinstance(status, bytes) else status
    assert status == "complete", status
    integrator = a.attrs["integrator"]
    integrator = integrator.decode() if isinstance(integrator, bytes) else integrator
    assert "cg + gamg" in integrator, integrator
    assert list(a["fields"]) == list(b["fields"]) and len(a["fields"]) == 21
    gap = max(np.abs(a["fields"][k][()] - b["fields"][k][()]).max() for k in a["fields"])
    scale = max(np.abs(b["fields"][k][()]).max() for k in b["fields"])
    assert gap <= 1e-8 * scale, f"fields differ by {gap / scale:.2e} of the largest"
    assert np.allclose(a["time_s"][()], b["time_s"][()], rtol=0, atol=1e-12)
    for name in ("strain_J", "kinetic_J", "dissipated_J", "external_work_J"):
        x, y = a["energy/" + name][()], b["energy/" + name][()]
        energy_gap = np.abs(x - y).max() / np.abs(y).max()
        assert energy_gap <= 1e-7, f"energy/{name} differs from the serial run's by {energy_gap:.2e} of its largest"
    e = a["energy"]
    balance = np.abs(e["kinetic_J"][()] + e["strain_J"][()] + e["dissipated_J"][()] - e["external_work_J"][()]).max()
    assert balance <= 1e-7 * e["external_work_J"][()].max(), f"energy balance off by {balance:.2e} J"
    strain = np.abs(a["energy/strain_J"][()] - b["energy/strain_J"][()]).max() / b["energy/strain_J"][()].max()
    assert (a["ksp_iterations"][1:] >= 1).all()
    print(f"fields within {gap / scale:.1e} of the serial run's; strain energy within {strain:.1e}; balance {balance:.1e} J")
PY
# An output directory under a file: every rank stops, the message names it, nothing is written.
touch "$work/a-file"
if "$mpiexec" -n 2 "$roifem_mpi" run "$scenarios/paper-full.toml" --out "$work/a-file/out" > "$work/bad.log" 2>&1; then
  echo "an unwritable --out succeeded"; exit 1
fi
grep -q "a-file" "$work/bad.log" || { cat "$work/bad.log"; exit 1; }
test ! -e "$work/a-file/out"
# Refusals every rank agrees on: said once, without MPI_ABORT's noise, nothing written.
refused() {  # refused LOG PATTERN COMMAND...
  local log=$1 pattern=$2
  shift 2
  if "$@" > "$log" 2>&1; then echo "succeeded: $*"; exit 1; fi
  [ "$(grep -c -- "$pattern" "$log")" -eq 1 ] || { echo "'$pattern' not said exactly once:"; cat "$log"; exit 1; }
  if grep -q "MPI_ABORT" "$log"; then echo "MPI_ABORT noise:"; cat "$log"; exit 1; fi
}
for command in run condense; do
  refused "$work/tools-$command.log" "has \[\[tool\]\]s ('left', 'right'); the distributed model takes loads only .*roifem run" \
    "$mpiexec" -n 2 "$roifem_mpi" "$command" "$scenarios/paper-spatulas-setup1.toml" --out "$work/tools-$command"
  test ! -e "$work/tools-$command"
done
refused "$work/typo.log" "PETSc options that nothing read .*: -ksp_typo cg" \
  "$mpiexec" -n 2 "$roifem_mpi" run "$scenarios/paper-full.toml" --out "$work/typo" -- -ksp_typo cg
test ! -e "$work/typo"
# SIGTERM (a batch system's, forwarded by mpirun) in a long run: every completed step is kept.
mesh=$(cd "$scenarios/../meshes" && pwd)/brain-800.msh
sed -e "s#^mesh = .*#mesh = \"$mesh\"#" -e 's/^steps = .*/steps = 1000000/' "$scenarios/paper-full.toml" > "$work/long.toml"
"$mpiexec" -n 2 "$roifem_mpi" run "$work/long.toml" --out "$work/term" > "$work/term.log" 2>&1 &
runner=$!
for _ in $(seq 100); do grep -q "^setup" "$work/term.log" 2>/dev/null && break; sleep 0.1; done
sleep 1
kill -TERM "$runner"
wait "$runner" || true
grep -q "stopped: interrupted by signal 15 after step [0-9]* of 1000000" "$work/term.log" || { cat "$work/term.log"; exit 1; }
/usr/bin/python3 "$(dirname "$0")/check_results.py" "$work/term/results.incomplete.h5" "incomplete: interrupted by signal 15" 10
test ! -e "$work/term/results.h5"
echo "mpi_run: passed"
