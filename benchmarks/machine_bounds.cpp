// SPDX-License-Identifier: GPL-3.0-or-later
// Machine bounds: what this machine's hardware allows the scale benchmark's two heaviest parts.
//   - DGEMM rate (OpenBLAS, all its threads): the ceiling for a supernodal factorization, whose
//     flops are mostly dense updates (the condensation setup of the 100k-node brain is 1.6e12).
//   - Streaming read bandwidth (a thread per core): the ceiling for a direct solve, which reads
//     its factor twice per step (the 100k-node brain's: 3.6e8 entries, 5.8 GB a step).
// Medians of repeated runs, printed as a table (roifem_scale_benchmark prints the same beside its).
//   compile with: cmake --build --preset release --target roifem_machine_bounds
//   sample run:   build/release/benchmarks/roifem_machine_bounds
#include <cstdio>

#include "scale/machine_bounds.hpp"

int main() {
  const roifem::bench::MachineBounds b = roifem::bench::measure_machine_bounds();
  std::printf("machine bounds (%d threads)\n", b.threads);
  std::printf("  dgemm n = 4000          %8.1f GFLOP/s   (1.6e12 flops: %.1f s at best)\n", b.dgemm_gflops,
              1.6e12 / (b.dgemm_gflops * 1e9));
  std::printf("  streaming read 400 MB   %8.1f GB/s      (5.8 GB a step: %.0f ms at best)\n", b.read_gb_per_s,
              5.8e3 / b.read_gb_per_s);
}
