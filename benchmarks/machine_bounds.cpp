// Machine bounds: what this machine's hardware allows the scale benchmark's two heaviest parts.
//   - DGEMM rate (OpenBLAS, all its threads): the ceiling for a supernodal factorization, whose
//     flops are mostly dense updates (the condensation setup of the 100k-node brain is 1.6e12).
//   - Streaming read bandwidth (OpenMP, all threads): the ceiling for a direct solve, which reads
//     its factor twice per step (the 100k-node brain's: 3.6e8 entries, 5.8 GB a step).
// Medians of repeated runs, printed as a table.
//   compile with: cmake --build --preset release --target roifem_machine_bounds
//   sample run:   build/release/benchmarks/roifem_machine_bounds
#include <cblas.h>
#include <omp.h>

#include <cstdio>
#include <vector>

#include "common/timer.hpp"
#include "simulation/run_loop.hpp"

namespace {

using roifem::Stopwatch;
using roifem::simulation::median;

double dgemm_gflops(int n, int repeats) {
  std::vector<double> A(static_cast<std::size_t>(n) * n, 1.0), B(A.size(), 0.5), C(A.size(), 0.0);
  std::vector<double> rates;
  for (int r = 0; r < repeats; ++r) {
    const Stopwatch clock;
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1.0, A.data(), n, B.data(), n, 0.0, C.data(), n);
    rates.push_back(2.0 * n * static_cast<double>(n) * n / clock.seconds() / 1e9);
  }
  return median(rates);
}

double read_gb_per_s(std::size_t bytes, int repeats) {
  const std::vector<double> x(bytes / sizeof(double), 1.0);
  std::vector<double> rates;
  double total = 0;
  for (int r = 0; r < repeats; ++r) {
    const Stopwatch clock;
    double sum = 0;
#pragma omp parallel for reduction(+ : sum)
    for (std::size_t i = 0; i < x.size(); ++i) sum += x[i];
    rates.push_back(static_cast<double>(bytes) / clock.seconds() / 1e9);
    total += sum;
  }
  if (total < 0) std::printf("unreachable\n");  // keeps the sums alive
  return median(rates);
}

}  // namespace

int main() {
  const double gflops = dgemm_gflops(4000, 5);
  const double gbs = read_gb_per_s(std::size_t{400} << 20, 7);
  std::printf("machine bounds (%d threads)\n", omp_get_max_threads());
  std::printf("  dgemm n = 4000          %8.1f GFLOP/s   (1.6e12 flops: %.1f s at best)\n", gflops, 1.6e12 / (gflops * 1e9));
  std::printf("  streaming read 400 MB   %8.1f GB/s      (5.8 GB a step: %.0f ms at best)\n", gbs, 5.8e3 / gbs);
}
