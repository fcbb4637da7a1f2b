#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Ctrl-C on a compare keeps what finished and draws it: SIGINT while a slow method runs stops the
# sweep inside that run; the trapezoid's runs that ended are in compare.csv, the plots are drawn,
# and the command exits 130 (interrupted).
# usage: compare_interrupted.sh ROIFEM SCENARIO_DIR WORK_DIR
set -eu
roifem=$1 scenarios=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
"$roifem" compare "$scenarios/paper-setup2.toml" --integrators trapezoid gsl-msbdf --tolerances 1e-10 \
  --out "$work/out" > "$work/log.txt" 2>&1 &
pid=$!
for _ in $(seq 600); do grep -q "^  (trapezoid:" "$work/log.txt" && break; sleep 0.1; done
sleep 1
kill -INT "$pid"
status=0
wait "$pid" || status=$?
cat "$work/log.txt"
[ "$status" -eq 130 ] || { echo "exit status $status, expected 130"; exit 1; }
grep -q "stopped: interrupted by signal 2.*runs that ended are kept" "$work/log.txt" || { echo "no word of the stop"; exit 1; }
rows=$(grep -c "^trapezoid,fixed," "$work/out/compare.csv")
[ "$rows" -eq 5 ] || { echo "compare.csv holds $rows of the trapezoid's 5 runs"; exit 1; }
[ -s "$work/out/work_precision.png" ] || { echo "no work_precision.png drawn"; exit 1; }
echo "ok: interrupted, kept $rows runs and drew them"
