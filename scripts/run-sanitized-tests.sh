#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the project with AddressSanitizer + UndefinedBehaviorSanitizer (the asan preset: line
# tables only, and no benchmarks, whose smoke tests run in Release) and runs the test suite under
# them. CI runs it after the Release tests. Third-party leaks (Gmsh, OpenCASCADE) are suppressed in
# tests/sanitizers/lsan.supp.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset asan >/dev/null
cmake --build --preset asan
ctest --preset asan -j 2 "$@"
