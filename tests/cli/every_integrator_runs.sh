#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Every row of the integrator table, run as a user runs it: `roifem run` on the paper's setup 1
# (forces) and on its spatulas (tools), linear and, for the rows marked [nonlinear], neo-Hookean and
# Ogden (one term, alpha = -20: brain tissue's exponent), two steps each (a step, its output, and
# the step after it). Each row runs on the forces scenario, or is refused there with exit 1 by a
# message naming it and then runs on the spatulas: every row completes a linear scenario, every
# [nonlinear] row a neo-Hookean and an Ogden one. Explicit rows and rows without a fixed step run error-controlled at rtol
# 1e-5 (an explicit fixed step would be far past the stability limit at the paper's dt); implicit
# rows with a fixed step take it, as a scenario without rtol gives (ARKODE's refused every
# neo-Hookean model that way).
# usage: every_integrator_runs.sh ROIFEM SCENARIO_DIR MESH_DIR WORK [LAW]
#   LAW: linear, neo-hookean or ogden (default: all three)
set -uo pipefail
roifem=$1 scenarios=$2 meshes=$3 work=$4 laws=${5:-"linear neo-hookean ogden"}
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work"
mkdir -p "$work"

# The rows, from the table as `roifem run --help` prints it: name, order, explicit/implicit, ...
"$roifem" run --help > "$work/help.txt" || fail "roifem run --help failed"
mapfile -t rows < <(grep -E '^  [a-z0-9-]+ +order [0-9]+ +(explicit|implicit) ' "$work/help.txt")
[ "${#rows[@]}" -ge 30 ] || fail "only ${#rows[@]} integrator rows found in roifem run --help"

# scenario NAME SOURCE LAW: the shipped scenario shortened to 2 steps of 10 ms.
scenario() {
  local name=$1 source=$2 law=$3
  sed -e "s#\.\./meshes/#$meshes/#" -e 's/^dt_s = .*/dt_s = 0.01/' -e 's/^steps = .*/steps = 2/' \
      -e 's/^field_every = .*/field_every = 1/' "$scenarios/$source" > "$work/$name.toml"
  if [ "$law" != linear ]; then
    sed -i -e '/^model = /d' -e 's/^preset = "paper".*/preset = "paper"\nmodel = "'"$law"'"/' "$work/$name.toml"
    [ "$law" = ogden ] && sed -i 's/^model = "ogden"/model = "ogden"\nogden_alpha = [-20.0]/' "$work/$name.toml"
  fi
}
for law in $laws; do
  if [ "$law" = linear ]; then
    scenario forces-linear paper-setup1.toml linear
    scenario spatulas-linear paper-spatulas-setup1.toml linear
  else
    scenario "forces-$law" paper-setup1.toml "$law"
    scenario "spatulas-$law" paper-spatulas-setup1-neo-hookean.toml "$law"
  fi
done

ran=0 refused=0
# run ROW CASE: 0 when it completed, 1 when refused by a message naming the row; fails otherwise.
run() {
  local name=$1 case=$2 dir="$work/runs/$1-$2" status=0
  mkdir -p "$dir"
  sed -e "s/^integrator = .*/integrator = \"$name\"/" "$work/$case.toml" > "$dir/case.toml"
  # Error-controlled where the method has no fixed step or is explicit (its fixed step would be far
  # past the stability limit); implicit methods with a fixed step take it, as a scenario without rtol.
  [ "$tolerance" = yes ] && sed -i 's/^steps = 2$/steps = 2\nrtol = 1e-5/' "$dir/case.toml"
  SECONDS=0
  "$roifem" run "$dir/case.toml" --out "$dir/out" > "$dir/stdout.txt" 2> "$dir/stderr.txt" || status=$?
  if [ "$status" -eq 0 ]; then
    [ -f "$dir/out/results.h5" ] || fail "$name on $case: exit 0 without results.h5"
    ran=$((ran + 1))
    echo "ran      $name on $case (${SECONDS} s)"
    return 0
  fi
  if [ "$status" -eq 1 ] && grep -q -- "$name" "$dir/stderr.txt"; then
    refused=$((refused + 1))
    echo "refused  $name on $case: $(tail -1 "$dir/stderr.txt" | cut -c1-160)"
    return 1
  fi
  fail "$name on $case: exit $status, and no refusal naming it: $(cat "$dir/stderr.txt")"
}

# Each row on the forces scenario of each law, and where it refuses that by name, on the spatulas.
for row in "${rows[@]}"; do
  read -r name _ _ kind rest <<<"$row"
  tolerance=no
  { [ "$kind" = explicit ] || [[ $rest == "adaptive "* ]]; } && tolerance=yes
  for law in $laws; do
    [ "$law" != linear ] && [[ $row != *"[nonlinear]"* ]] && continue
    run "$name" "forces-$law" || run "$name" "spatulas-$law" || fail "$name completed no $law scenario"
  done
done
echo "ok: ${#rows[@]} rows, $ran runs completed, $refused refused by name"
