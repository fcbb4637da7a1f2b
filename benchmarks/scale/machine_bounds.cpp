// SPDX-License-Identifier: GPL-3.0-or-later
#include "scale/machine_bounds.hpp"
#include "common/format.hpp"

#include <cblas.h>

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <thread>
#include <vector>

#include "common/timer.hpp"
#include "io/csv.hpp"
#include "scale/child_process.hpp"
#include "simulation/run_loop.hpp"

namespace roifem::bench {

namespace {

double dgemm_gflops(int n, int repeats) {
  std::vector<double> A(static_cast<std::size_t>(n) * n, 1.0), B(A.size(), 0.5), C(A.size(), 0.0);
  std::vector<double> rates;
  for (int r = 0; r < repeats; ++r) {
    const Stopwatch clock;
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1.0, A.data(), n, B.data(), n, 0.0, C.data(), n);
    rates.push_back(2.0 * n * static_cast<double>(n) * n / clock.seconds() / 1e9);
  }
  return simulation::median(rates);
}

/// Each thread sums its contiguous share of x; the sums are kept, so nothing is optimized away.
double read_gb_per_s(std::size_t bytes, int repeats, int threads) {
  const std::vector<double> x(bytes / sizeof(double), 1.0);
  std::vector<double> rates, sums(static_cast<std::size_t>(threads));
  const std::size_t share = (x.size() + static_cast<std::size_t>(threads) - 1) / static_cast<std::size_t>(threads);
  double total = 0;
  for (int r = 0; r < repeats; ++r) {
    const Stopwatch clock;
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        const std::size_t first = std::min(x.size(), static_cast<std::size_t>(t) * share);
        const std::size_t last = std::min(x.size(), first + share);
        double sum = 0;
        for (std::size_t i = first; i < last; ++i) sum += x[i];
        sums[static_cast<std::size_t>(t)] = sum;
      });
    for (auto& thread : pool) thread.join();
    rates.push_back(static_cast<double>(bytes) / clock.seconds() / 1e9);
    for (double s : sums) total += s;
  }
  if (total < 0) rates.push_back(0);  // unreachable: keeps the sums alive
  return simulation::median(rates);
}

}  // namespace

MachineBounds measure_machine_bounds() {
  MachineBounds b;
  b.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  b.dgemm_gflops = dgemm_gflops(4000, 5);
  b.read_gb_per_s = read_gb_per_s(std::size_t{400} << 20, 7, b.threads);
  return b;
}

std::string MachineBounds::serialize() const {
  std::ostringstream out;
  out.precision(17);
  out << "threads=" << threads << "\ndgemm_gflops=" << dgemm_gflops << "\nread_gb_per_s=" << read_gb_per_s << "\n";
  return out.str();
}

MachineBounds MachineBounds::parse(const std::string& text) {
  const auto f = parse_key_values(text);
  return {std::stoi(f.at("threads")), std::stod(f.at("dgemm_gflops")), std::stod(f.at("read_gb_per_s"))};
}

void report_machine_bounds(const std::filesystem::path& out) {
  const ChildResult child = run_in_child([] { return measure_machine_bounds().serialize(); }, 300);
  if (!child.ok) {
    std::printf("Machine bounds: not measured (%s)\n", child.output.c_str());
    return;
  }
  const MachineBounds b = MachineBounds::parse(child.output);
  std::printf(
      "Machine: %d threads, DGEMM %.1f GFLOP/s (a factorization's ceiling), streaming read %.1f GB/s (a direct "
      "solve's)\n",
      b.threads, b.dgemm_gflops, b.read_gb_per_s);
  io::CsvWriter csv(out / "machine.csv", "threads,dgemm_gflops,read_gb_per_s");
  csv.row(format("%d,%.6g,%.6g", b.threads, b.dgemm_gflops, b.read_gb_per_s));
  csv.close();
}

}  // namespace roifem::bench
