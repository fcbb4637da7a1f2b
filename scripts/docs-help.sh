#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Writes docs/commands.md: the table of commands, then each command's --help as the CLI prints it
# (the docs check, tests/docs/check_docs.py, compares every quoted help text with the CLI's).
# usage: scripts/docs-help.sh [ROIFEM [ROIFEM_MPI]]   (default: the Release build's)
set -euo pipefail
cd "$(dirname "$0")/.."
roifem=${1:-build/release/src/app/roifem}
roifem_mpi=${2:-build/release/src/app/roifem-mpi}
out=docs/commands.md
{
  cat <<'MD'
# Commands

`roifem` (and `roifem-mpi`) are built into `build/release/src/app/` by either of the README's
commands, and installed into `PREFIX/bin` by `cmake --install`. Every command explains its options
with `--help` (or `roifem help COMMAND`); a misspelt command, option, scenario key, integrator,
reduction or set is named with the nearest valid one. Lengths on the command line and in files are
millimetres. Exit codes: 0 done; 1 an error in the input, the model or a solver (the message names
the file and line, key, node, element or step); 2 a command-line error; 130 / 143 stopped by
Ctrl-C / SIGTERM (every completed step kept).

| command | what | guide |
|---|---|---|
| `roifem paper --out results/paper` | the Hansen & Larsen (1998) experiment: findings, Table 2, plots, the error budget | [paper.md](paper.md), [accuracy.md](accuracy.md) |
| `roifem run scenarios/paper-setup1.toml --out results/setup1` | one scenario: `results.h5` and `results.xdmf`; with `--from DIR/results.h5 [--step K]`, it goes on from a restart point of an earlier run | [results.md](results.md), [../scenarios/README.md](../scenarios/README.md) |
| `roifem compare scenarios/paper-setup2.toml --out results/compare` | every integrator against the exact modal solution: errors, cost, stability limits | [integrators.md](integrators.md) |
| `roifem energy scenarios/paper-full-neo-hookean-undamped.toml --out results/energy` | each integrator's energy balance over an (undamped) run: how far each drifts | [large-deformation.md](large-deformation.md) |
| `roifem roi-size scenarios/paper-setup1.toml --max-error-mm 0.5` | how large an ROI an error budget needs, per reduction | [paper.md](paper.md) |
| `roifem convergence scenarios/paper-setup1.toml --nodes 800 5000 20000 --out results/convergence` | the brain at several sizes: observed orders, extrapolated values | [accuracy.md](accuracy.md) |
| `roifem model-error scenarios/paper-setup1.toml --out results/model-error` | small strain against CalculiX's geometrically nonlinear answer | [accuracy.md](accuracy.md) |
| `roifem fit data/budday2017-brain.csv --out results/fit` | a law fitted to measured tissue (Budday et al. 2017's human brain curves): parameters, RMSE per region and mode, plots, `[material]` tables | [materials.md](materials.md) |
| `roifem mesh --nodes 800 --out results/brain.msh` | a brain mesh: the ellipsoid (Gmsh), or from an image (`--colin27`, `--image`; CGAL) | [anatomy.md](anatomy.md) |
| `roifem info meshes/brain-800.msh` | a mesh's size, volume, quality, bounding box and named sets | |
| `roifem serve scenarios/paper-setup1.toml` | a page on which you steer the brain live: drag a tool, see it deform, feel the force, switch models | [simulator.md](simulator.md) |
| `scripts/mpirun.sh -n 2 roifem-mpi run scenarios/paper-full.toml --out results/mpi` | the full model on P ranks (PETSc, MPI, MUMPS); also `condense`, `compare` | [mpi.md](mpi.md) |

The help texts below are the CLI's own (`scripts/docs-help.sh` writes this page; the docs check
compares them).
MD
  echo
  echo "## roifem"
  echo
  echo "<!-- help: -->"
  echo '```'
  "$roifem" --help
  echo '```'
  for command in paper run compare energy roi-size convergence model-error fit mesh info serve; do
    echo
    echo "## roifem $command"
    echo
    echo "<!-- help: $command -->"
    echo '```'
    "$roifem" "$command" --help
    echo '```'
  done
  if [ -x "$roifem_mpi" ]; then
    for command in "" run condense compare; do
      echo
      echo "## roifem-mpi${command:+ $command}"
      echo
      echo "<!-- help-mpi: $command -->"
      echo '```'
      if [ -n "$command" ]; then "$roifem_mpi" "$command" --help; else "$roifem_mpi" --help; fi
      echo '```'
    done
  fi
} > "$out.partial"
mv "$out.partial" "$out"
echo "wrote $out"
