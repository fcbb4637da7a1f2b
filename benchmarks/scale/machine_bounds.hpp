// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What this machine's hardware allows the scale benchmark's two heaviest parts, measured:
///   - the DGEMM rate (the BLAS CHOLMOD uses, all its threads): the ceiling of a supernodal
///     factorization, whose flops are mostly dense updates;
///   - the streaming read bandwidth (one std::thread per core): the ceiling of a direct solve,
///     which reads its factor twice per step.
/// Medians of repeated runs. The VM behind one name can differ between sessions by 2-3x in both,
/// so the scale table prints them beside its figures.
#include <filesystem>
#include <string>

namespace roifem::bench {

struct MachineBounds {
  int threads = 0;           ///< cores the read ran on
  double dgemm_gflops = 0;   ///< n = 4000, median of 5
  double read_gb_per_s = 0;  ///< 400 MB, median of 7

  /// "key=value" lines (to pass through a child process) and back.
  std::string serialize() const;
  static MachineBounds parse(const std::string& text);
};

MachineBounds measure_machine_bounds();

/// Measures the bounds in a child process (as the benchmarks measure their models), prints them
/// before a benchmark's table (the VM behind one name differs between sessions by 2-3x in both)
/// and writes DIR/machine.csv.
void report_machine_bounds(const std::filesystem::path& out);

}  // namespace roifem::bench
