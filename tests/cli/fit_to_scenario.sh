#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A fitted [material] table pasted into a scenario, as a user would: the paper's setup 1 with its
# [material] table replaced by roifem fit's DIR/material-REGION-LAW.toml, two steps, run by
# `roifem run`; its resolved scenario must carry the fitted law and moduli.
# usage: fit_to_scenario.sh ROIFEM SCENARIO_DIR MESH_DIR TABLE WORK
set -euo pipefail
roifem=$1 scenarios=$2 meshes=$3 table=$4 work=$5
rm -rf "$work" && mkdir -p "$work"
# Everything but the [material] table (its header and its one line), then the fitted table.
sed -e "s#\.\./meshes/#$meshes/#" -e 's/^steps = .*/steps = 2/' -e '/^\[material\]/,/^preset/d' \
  "$scenarios/paper-setup1.toml" > "$work/scenario.toml"
cat "$table" >> "$work/scenario.toml"
"$roifem" run "$work/scenario.toml" --out "$work/out"
/usr/bin/python3 - "$work/out/results.h5" "$table" <<'PY'
import re, sys, h5py
f = h5py.File(sys.argv[1], "r")
resolved = f["scenario"][()].decode() if "scenario" in f else f.attrs["scenario"]  # a dataset beyond 64 KiB
resolved = resolved.decode() if isinstance(resolved, bytes) else resolved
table = open(sys.argv[2]).read()
for key in ("model", "mu_Pa", "lambda_Pa", "ogden_alpha"):
    m = re.search(rf"^{key} = (.*)$", table, re.M)
    if not m:
        continue
    want = m.group(1).strip()
    got = re.search(rf"^{key} = (.*)$", resolved, re.M)
    if not got:
        sys.exit(f"FAIL: the resolved scenario has no {key}")
    a, b = want.strip('[]"'), got.group(1).strip().strip('[]"')
    same = a == b or (re.match(r"^[-0-9.e+]+$", a) and abs(float(a) - float(b)) <= 1e-9 * abs(float(a)))
    if not same:
        sys.exit(f"FAIL: {key} is {got.group(1)} in the run, {want} in the fitted table")
print("ok: the fitted table ran and the run's resolved scenario carries it")
PY
