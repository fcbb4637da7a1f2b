#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the project with AddressSanitizer + UndefinedBehaviorSanitizer (the asan preset: -O1, line
# tables only, no benchmarks and no PETSc engine, whose tests run in Release) and runs the test
# suite under them, less the tests labelled slow (docs/testing.md: what runs their code here
# instead). CI runs it after the Release tests. Third-party leaks (Gmsh, OpenCASCADE) are suppressed
# in tests/sanitizers/lsan.supp. ctest options pass through.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset asan >/dev/null
cmake --build --preset asan
ctest --preset asan -j 2 "$@"
