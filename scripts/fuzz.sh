#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the libFuzzer harnesses (fuzz/*_fuzzer.cpp, with Debian's clang, ASan and UBSan) and runs
# each on its committed corpus (fuzz/corpus/NAME).
#   scripts/fuzz.sh                 what CI runs: a fixed seed and a fixed number of inputs per
#                                   harness (about a minute each), so that a run is repeatable
#   scripts/fuzz.sh --seconds N     exploring: a random seed, N seconds per harness; merge what it
#                                   finds into the corpus with  build/fuzz/NAME_fuzzer -merge=1 fuzz/corpus/NAME build/fuzz/corpus-NAME
# A crash leaves its input as build/fuzz/crash-* and fails the script.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=()
if [ "${1:-}" = --seconds ]; then
  mode=(-max_total_time="${2:?--seconds needs a number}")
fi
out=build/fuzz
mkdir -p "$out"
# -DNDEBUG as in the shipped build: toml++ 3.3's internal debug assertions fire on some malformed
# keys ('[#' in a table header) that its release build reports as a clean parse error.
flags=(-std=c++20 -O1 -g -DNDEBUG -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -I src -I /usr/include/eigen3)
# Each harness is built from the few sources it exercises (instrumented); the rest of what they
# reference (the reductions' basis makers, which the reduction table names) comes from the release
# build's core library, uninstrumented: the harness's own definitions take precedence over it.
declare -A sources=(
  [scenario_reader]="src/scenario/scenario_reader.cpp src/scenario/toml_text_guard.cpp src/fem/material.cpp src/condensation/reduction.cpp"
  [mesh_checks]="src/mesh/mesh_checks.cpp src/mesh/tet_mesh.cpp"
  [trajectory_reader]="src/scenario/trajectory_reader.cpp src/model/load_history.cpp"
  [nifti_header]="src/anatomy/image_volume.cpp"
)
declare -A libraries=([nifti_header]="-I /usr/include/nifti -lnifti2 -lznz -lz")
# Dictionaries: the keys, tables and values a reader recognizes (fuzz/NAME.dict), where one helps.
declare -A dictionaries=([scenario_reader]="-dict=fuzz/scenario_reader.dict")
core=build/release/src
[ -e "$core/libroifem_core.so" ] || { cmake --preset release >/dev/null && cmake --build --preset release --target roifem_core; }
for name in scenario_reader mesh_checks trajectory_reader nifti_header; do
  # shellcheck disable=SC2086
  clang++ "${flags[@]}" "fuzz/${name}_fuzzer.cpp" ${sources[$name]} -L"$core" -lroifem_core -Wl,-rpath,"$PWD/$core" \
    ${libraries[$name]:-} -o "$out/${name}_fuzzer"
  work="$out/corpus-$name"
  rm -rf "$work"
  cp -r "fuzz/corpus/$name" "$work"  # new inputs go to the copy; the committed corpus stays as it is
  if [ ${#mode[@]} -eq 0 ]; then
    declare -A runs=([scenario_reader]=150000 [mesh_checks]=600000 [trajectory_reader]=400000 [nifti_header]=60000)
    limits=(-seed=1 -runs="${runs[$name]}")
  else
    limits=("${mode[@]}")
  fi
  echo "fuzzing $name: ${limits[*]} (corpus: $(ls "$work" | wc -l) inputs)"
  rm -f "$out"/crash-* "$out"/leak-* "$out"/timeout-* "$out"/oom-*
  status=0
  # shellcheck disable=SC2086
  "$out/${name}_fuzzer" "${limits[@]}" ${dictionaries[$name]:-} -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$out/" "$work" \
    > "$out/$name.log" 2>&1 || status=$?
  grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb)|ERROR|SUMMARY" "$out/$name.log" || true
  if [ "$status" -ne 0 ]; then
    echo "fuzzing $name failed (exit $status); input: $(ls "$out"/crash-* "$out"/leak-* "$out"/timeout-* "$out"/oom-* 2>/dev/null)"
    tail -n 40 "$out/$name.log"
    exit 1
  fi
done
echo "fuzzing: no crash"
