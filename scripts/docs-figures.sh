#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates the pictures docs/ shows, each from the command beside it in the guide:
#   docs/colin27-20k.png  the Colin27 brain at 20k nodes (roifem mesh --colin27 --nodes 20000), its surface sets
#   docs/colin27-800.png  the shipped meshes/colin27-800.msh with its opening and base
#   docs/incision-*.png, docs/colin27-incision-*.png  the brain scenarios of a cut (docs/cutting.md):
#                         setup 1's run through the incision (-cut.png) and its tools' forces against
#                         the full model's (-forces.png)
# and rewrites docs/commands.md from the CLI's --help (scripts/docs-help.sh).
# usage: scripts/docs-figures.sh   (after a Release build; the 20k mesh takes about half a minute)
set -euo pipefail
cd "$(dirname "$0")/.."
roifem=build/release/src/app/roifem
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$roifem" mesh --colin27 --nodes 20000 --out "$work/colin27-20k.msh"
/usr/bin/python3 scripts/plots/plot_mesh.py "$work/colin27-20k.msh" docs/colin27-20k.png
/usr/bin/python3 scripts/plots/plot_mesh.py meshes/colin27-800.msh docs/colin27-800.png opening_left opening_right opening_floor base
for brain in incision colin27-incision; do
  for model in full setup1; do "$roifem" run "scenarios/$brain-$model.toml" --out "$work/$brain-$model" >/dev/null; done
  /usr/bin/python3 scripts/plots/plot_mesh.py "$work/$brain-setup1/results.h5" "docs/$brain-cut.png"
  /usr/bin/python3 scripts/plots/plot_tool_forces.py "docs/$brain-forces.png" "$work/$brain-full" "$work/$brain-setup1"
done
scripts/docs-help.sh
echo "docs figures: docs/colin27-20k.png, docs/colin27-800.png, docs/{,colin27-}incision-{cut,forces}.png, docs/commands.md"
