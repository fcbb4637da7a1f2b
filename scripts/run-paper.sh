#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sets up (Debian packages), builds (Release) and runs the paper experiment on meshes/brain-800.msh:
# prints Table 2 and writes results/paper/{errors.csv,timing.csv,results.h5,*.png}.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release
build/release/src/app/roifem paper --out "${1:-results/paper}"
