#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A compare killed mid-sweep keeps the runs that ended: compare.csv is rewritten (atomically) as each
# run ends, so the trapezoid's rows are there when a slow method is killed.
# usage: compare_killed.sh ROIFEM SCENARIO_DIR WORK_DIR
set -eu
roifem=$1 scenarios=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
"$roifem" compare "$scenarios/paper-setup2.toml" --integrators trapezoid gsl-msbdf --tolerances 1e-10 --no-plots \
  --out "$work/out" > "$work/log.txt" 2>&1 &
pid=$!
for _ in $(seq 300); do grep -q "gsl-msbdf" "$work/out/compare.csv" 2>/dev/null && break; grep -q "^  (trapezoid:" "$work/log.txt" && break; sleep 0.1; done
sleep 1
kill -KILL "$pid"
wait "$pid" 2>/dev/null || true
cat "$work/log.txt"
rows=$(grep -c "^trapezoid,fixed," "$work/out/compare.csv")
[ "$rows" -eq 5 ] || { echo "compare.csv holds $rows of the trapezoid's 5 runs"; exit 1; }
echo "ok: kept $rows runs"
