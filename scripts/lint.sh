#!/usr/bin/env bash
# Lint: the formatter check (clang-format 14, .clang-format) on every tracked C++ file, then
# clang-tidy 14 (.clang-tidy: the checks and why) on every translation unit of src/ and
# integrators/, zero findings allowed. Needs the release build's compile_commands.json
# (scripts/run-tests.sh makes it).
#   --fix       apply the formatter instead of checking
#   --analyzer  also the Clang static analyzer checks of .clang-tidy (core, C++): three times the
#               time per unit, 9.3 min in all on 2 cores against 6.5), so CI leaves them out; run it before a release
#               or after touching memory handling (it found a possible null BLAS setter call)
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
if [[ "${1:-}" == "--fix" ]]; then
  clang-format-14 -i "${files[@]}"
  exit 0
fi
echo "lint: clang-format on ${#files[@]} files"
clang-format-14 --dry-run -Werror "${files[@]}"
[ -f build/release/compile_commands.json ] || { echo "lint: build/release/compile_commands.json missing (run scripts/run-tests.sh first)" >&2; exit 2; }
mapfile -t units < <(git ls-files 'src/*.cpp' 'integrators/*.cpp')
checks=()
[[ "${1:-}" == "--analyzer" ]] || checks=(-checks=-clang-analyzer-*)
echo "lint: clang-tidy on ${#units[@]} translation units${checks[*]:+ (${checks[*]})}"
start=$SECONDS
run-clang-tidy-14 -quiet -p build/release -j "$(nproc)" "${checks[@]}" "${units[@]}" > build/clang-tidy.log 2>&1 || {
  grep -E "(warning|error):" build/clang-tidy.log | sort -u >&2
  echo "lint: clang-tidy findings (full log: build/clang-tidy.log)" >&2
  exit 1
}
echo "lint: clean ($((SECONDS - start)) s)"
