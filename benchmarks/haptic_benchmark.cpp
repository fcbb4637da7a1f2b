// SPDX-License-Identifier: GPL-3.0-or-later
// Haptic: a surgeon's tool steered at the device's rate (1 kHz) on condensed brains. Per brain and
// ROI (each in its own child process): the plain condensed step and the haptic tick (the hand's
// new position in, the step, the tool's force out; integrators/haptic_trapezoid.hpp), 10,000 of
// each taking turns in blocks, with their medians, tails and late ticks (over 1 ms) per 10,000 and
// what the late ones met (preemption by another process, a page fault); and a control loop that
// streams the factor's bytes at the same tick length, the machine's own jitter. Writes DIR/haptic.csv.
//   compile with: cmake --build --preset release --target roifem_haptic_benchmark
//   sample run:   build/release/benchmarks/roifem_haptic_benchmark --nodes 20000 100000 --rois 300 1000
//                   --out results/haptic
#include <CLI/CLI.hpp>

#include <cstdio>

#include "brain_meshes.hpp"
#include "common/format.hpp"
#include "haptic/haptic_model.hpp"
#include "io/csv.hpp"
#include "scale/child_process.hpp"
#include "scale/machine_bounds.hpp"

namespace roifem::bench {
namespace {

struct Options {
  std::vector<long> nodes{20000, 100000};
  std::vector<long> rois{300, 1000};
  HapticOptions haptic;
  std::filesystem::path out = "haptic-results";
  double model_timeout_s = 1800;
  bool machine_bounds = true;
};

/// "0.412 0.602 0.731 1.20 3" : median, p99, p99.9, max (ms), late per 10,000.
std::string stats_text(const TickStats& t, long ticks) {
  return format("%7.3f %7.3f %7.3f %7.2f %6.1f", t.median * 1e3, t.p99 * 1e3, t.p999 * 1e3, t.max * 1e3,
                1e4 * static_cast<double>(t.late) / static_cast<double>(ticks));
}

std::string stats_csv(const TickStats& t) {
  return format("%.6g,%.6g,%.6g,%.6g,%ld,%ld,%ld,%ld,%ld", t.median * 1e3, t.p99 * 1e3, t.p999 * 1e3, t.max * 1e3, t.late,
                t.late_preempted, t.late_page_fault, t.page_faults, t.preemptions);
}

int run(const Options& o) {
  std::filesystem::create_directories(o.out);
  if (o.machine_bounds) report_machine_bounds(o.out);
  const long ticks = o.haptic.ticks;
  const double deadline_ms = 1e3 / o.haptic.rate_hz;
  std::string columns;
  for (const char* who : {"plain", "haptic", "control", "nonlinear"})
    for (const char* what :
         {"median_ms", "p99_ms", "p999_ms", "max_ms", "late", "late_preempted", "late_page_fault", "page_faults", "preemptions"})
      columns += std::string(",") + who + "_" + what;
  io::CsvWriter csv(o.out / "haptic.csv",
                    "nodes,roi_nodes,system_dofs,interface_dofs,tool_nodes,setup_s,attach_ms,"
                    "peak_force_N,ticks,rate_hz,blas_threads,memory_locked" +
                        columns + ",tick_vs_step,newton_iterations,newton_residual,force_error_rel,nonlinear_vs_tick");
  std::printf(
      "Haptic: %ld ticks at %.0f Hz (dt = %.3g ms, deadline %.3g ms); a tool on the %ld wall nodes nearest the target; "
      "plain = the condensed step (load, step, displacement out), tick = the hand's position in, the step, force and "
      "displacement out; control = a read of the factor's dense block's bytes, as long as the plain step\n",
      ticks, o.haptic.rate_hz, deadline_ms, deadline_ms, o.haptic.tool_nodes);
  std::printf("%8s %5s %6s %6s %5s %8s | %-38s | %-38s | %-38s | %6s  %s\n", "nodes", "ROI", "dofs", "iface", "tool", "attach",
              "plain step: median p99 p99.9 max (ms) late", "haptic tick: median p99 p99.9 max late",
              "control: median p99 p99.9 max late", "tick/", "late ticks met");
  for (long n : o.nodes) {
    const auto mesh_file = brain_mesh_file(n);
    for (long roi : o.rois) {
      const ChildResult child =
          run_in_child([&] { return measure_haptic(mesh_file, roi, o.haptic).serialize(); }, o.model_timeout_s);
      if (!child.ok) {
        std::printf("%8ld %5ld  failed: %s\n", n, roi, child.output.c_str());
        csv.row(format("%ld,%ld,,,,,,,,,,", n, roi));
        continue;
      }
      const HapticMeasurement m = HapticMeasurement::parse(child.output);
      const double ratio = m.haptic.median / m.plain.median;
      std::printf("%8ld %5ld %6ld %6ld %5ld %6.0fms | %-38s | %-38s | %-38s | %5.2fx  %ld preempted, %ld page fault%s\n", m.nodes,
                  m.roi_nodes, m.system_dofs, m.interface_dofs, m.tool_nodes, m.attach_s * 1e3,
                  stats_text(m.plain, ticks).c_str(), stats_text(m.haptic, ticks).c_str(), stats_text(m.control, ticks).c_str(),
                  ratio, m.haptic.late_preempted, m.haptic.late_page_fault, m.memory_locked ? " (memory locked)" : "");
      std::fflush(stdout);
      csv.row(format("%ld,%ld,%ld,%ld,%ld,%.6g,%.6g,%.6g,%ld,%.6g,%d,%d,", m.nodes, m.roi_nodes, m.system_dofs, m.interface_dofs,
                     m.tool_nodes, m.setup_s, m.attach_s * 1e3, m.peak_force_N, ticks, o.haptic.rate_hz, m.blas_threads,
                     m.memory_locked ? 1 : 0) +
              stats_csv(m.plain) + "," + stats_csv(m.haptic) + "," + stats_csv(m.control) + "," + stats_csv(m.nonlinear) +
              format(",%.6g,%d,%.6g,%.6g,%.6g", ratio, m.newton_iterations, m.newton_residual, m.force_error_rel,
                     m.newton_iterations > 0 ? m.nonlinear.median / m.haptic.median : 0.0));
      if (m.newton_iterations > 0 && m.nonlinear_ticks > 0)
        std::printf(
            "%8s %5s  nonlinear tick (hybrid ROI, %d modified-Newton iterations, hand x %g): %s (ms, late per 10,000); "
            "%.2fx the linear tick; Newton residual after them %.1e; force %.1e from a converged step's%s\n",
            "", "", m.newton_iterations, o.haptic.hand_scale, stats_text(m.nonlinear, m.nonlinear_ticks).c_str(),
            m.nonlinear.median / m.haptic.median, m.newton_residual, m.force_error_rel,
            m.nonlinear_ticks < ticks ? format(" (stopped after %ld ticks)", m.nonlinear_ticks).c_str() : "");
      else if (m.newton_iterations > 0)
        std::printf("%8s %5s  nonlinear tick: stopped before its first timed tick (its message above)\n", "", "");
    }
  }
  csv.close();
  std::printf(
      "(late: ticks over %.3g ms per 10,000; late ticks met: of the haptic tick's late ones, how many saw an "
      "involuntary context switch or a page fault)\nwrote %s\n",
      deadline_ms, (o.out / "haptic.csv").c_str());
  return 0;
}

}  // namespace
}  // namespace roifem::bench

int main(int argc, char** argv) {
  using namespace roifem::bench;
  Options o;
  CLI::App app{
      "roifem haptic benchmark: a tool steered at a haptic device's rate on condensed brains; the tick\n"
      "(position in, condensed step, force out) beside the plain condensed step, with tails and late\n"
      "ticks. Meshes are generated once and cached in $ROIFEM_MESH_CACHE (default ./bench-meshes)."};
  app.add_option("--nodes", o.nodes, "brain sizes (nodes)")->capture_default_str();
  app.add_option("--rois", o.rois, "ROI sizes (nodes nearest the target)")->capture_default_str();
  app.add_option("--tool-nodes", o.haptic.tool_nodes, "wall nodes the tool holds")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--ticks", o.haptic.ticks, "timed ticks of each kind")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--rate", o.haptic.rate_hz, "the device's rate (Hz): the time step and the deadline")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--blas-threads", o.haptic.blas_threads, "BLAS threads (0: as the BLAS starts)")->capture_default_str();
  app.add_flag("--lock-memory", o.haptic.lock_memory,
               "mlockall the model before timing (rules out paging; made every step about 35% slower on the 2-core test VM)");
  app.add_option("--out", o.out, "directory for haptic.csv")->capture_default_str();
  app.add_option("--model-timeout", o.model_timeout_s, "seconds after which one model is stopped and its row marked failed")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_flag("!--no-machine-bounds", o.machine_bounds, "skip measuring the machine's bounds (smoke tests)");
  app.add_option("--hand-scale", o.haptic.hand_scale, "the nonlinear tick's hand path, scaled (the linear tick's: 1)")
      ->capture_default_str();
  app.add_option("--newton-iterations", o.haptic.newton_iterations,
                 "the nonlinear tick's modified-Newton iterations (the hybrid ROI, neo-Hookean; 0: no nonlinear tick)")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roifem_haptic_benchmark: %s\n", e.what());
    return 1;
  }
}
