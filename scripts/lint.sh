#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Lint: the layer check (scripts/check_layers.py), the formatter check (clang-format 14, .clang-format) on every tracked C++ file, then
# clang-tidy 14 (.clang-tidy: the checks and why) on every source of src/ and integrators/, zero
# findings allowed. Needs the release build's compile_commands.json (scripts/run-tests.sh makes it).
#   --fix       apply the formatter instead of checking
#   --unity     clang-tidy on the asan build's unity units instead. Without it, the release
#               build's units when it is a unity build (the release preset is; what CI runs): the
#               same sources and checks in a quarter of the time of one unit per source
#   --analyzer  also the Clang static analyzer checks of .clang-tidy (core, C++): three times the
#               time per unit, 9.3 min in all on 2 cores against 6.5), so CI leaves them out; run it before a release
#               or after touching memory handling (it found a possible null BLAS setter call)
set -euo pipefail
cd "$(dirname "$0")/.."
# The layers (docs/architecture.md): no #include runs back up.
/usr/bin/python3 scripts/check_layers.py .
mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
if [[ "${1:-}" == "--fix" ]]; then
  clang-format-14 -i "${files[@]}"
  exit 0
fi
echo "lint: clang-format on ${#files[@]} files"
clang-format-14 --dry-run -Werror "${files[@]}"
# Not the one CGAL unit: its 114 lines take 100 s of clang-tidy, all of it in CGAL's templates.
mapfile -t sources < <(git ls-files 'src/*.cpp' 'integrators/*.cpp' | grep -v '^src/anatomy/image_mesher.cpp$')
disabled=-clang-analyzer-*
[[ "${1:-}" == "--analyzer" ]] && disabled=""
options=()
# The release preset is a unity build too: without --unity, its units are linted the same way.
unity_db=""
if [[ "${1:-}" == "--unity" ]]; then
  unity_db=build/asan
elif [ -f build/release/compile_commands.json ] && grep -q '/Unity/unity_' build/release/compile_commands.json; then
  unity_db=build/release
fi
if [[ -n "$unity_db" ]]; then
  # The asan preset's unity units (8 sources each, so Eigen's headers are parsed once per unit, not
  # per source: 127 s instead of about 500 on 2 cores), with the included sources diagnosed like headers
  # (and the unit's own #include of .cpp files not a finding). Every source must be in a unit.
  db=$unity_db
  [ -f $db/compile_commands.json ] || { echo "lint: $db/compile_commands.json missing (run scripts/run-sanitized-tests.sh first)" >&2; exit 2; }
  mapfile -t units < <(grep -o '"file": "[^"]*/\(src\|integrators\)/[^"]*/Unity/unity_[0-9]*_cxx\.cxx"' $db/compile_commands.json | cut -d'"' -f4)
  # A source CMake keeps out of the units (one with its own COMPILE_DEFINITIONS, as
  # common/version.cpp) is linted as its own translation unit.
  standalone=()
  for source in "${sources[@]}"; do
    grep -q "^#include \"$PWD/$source\"" "${units[@]}" && continue
    grep -q "\"file\": \"$PWD/$source\"" $db/compile_commands.json || { echo "lint: $source is in neither a unity unit nor the compile database of $db (run scripts/lint.sh without --unity)" >&2; exit 2; }
    standalone+=("$source")
  done
  units+=("${standalone[@]}")
  disabled+=,-bugprone-suspicious-include
  options+=("-header-filter=(src|integrators)/.*\.(hpp|cpp)$")
  echo "lint: clang-tidy on ${#sources[@]} sources in $((${#units[@]} - ${#standalone[@]})) unity units and ${#standalone[@]} alone (checks: .clang-tidy,$disabled)"
else
  db=build/release
  [ -f $db/compile_commands.json ] || { echo "lint: $db/compile_commands.json missing (run scripts/run-tests.sh first)" >&2; exit 2; }
  units=("${sources[@]}")
  echo "lint: clang-tidy on ${#units[@]} translation units (checks: .clang-tidy${disabled:+,$disabled})"
fi
start=$SECONDS
run-clang-tidy-14 -quiet -p $db -j "$(nproc)" ${disabled:+"-checks=$disabled"} "${options[@]}" "${units[@]}" > build/clang-tidy.log 2>&1 || {
  grep -E "(warning|error):" build/clang-tidy.log | sort -u >&2
  echo "lint: clang-tidy findings (full log: build/clang-tidy.log)" >&2
  exit 1
}
echo "lint: clean ($((SECONDS - start)) s)"
