// SPDX-License-Identifier: GPL-3.0-or-later
// Scale: the full brain model and condensed ROI models at realistic resolutions, each measured in
// its own child process (setup split into assembly, factorization and condensation; per-step
// median and p99; memory peak; frame rate), with ratios to the full model of the same brain taken
// in the same run; then the largest ROI that holds a haptic rate. Prints the machine's bounds (its
// DGEMM rate and streaming read bandwidth, scale/machine_bounds.hpp) and a table, writes
// DIR/machine.csv, DIR/scale.csv (and DIR/haptic.csv) and DIR/scale.png.
//   compile with: cmake --build --preset release --target roifem_scale_benchmark
//   sample run:   build/release/benchmarks/roifem_scale_benchmark --nodes 800 5000 20000 100000 300000
//                   --rois 300 1000 3% --haptic 20000 100000 300000 --full-cg 100000 300000 --out results/scale
//   neo-Hookean:  build/release/benchmarks/roifem_scale_benchmark --nodes 20000 --rois none --neo-hookean 20000
//                   --out results/scale-nh
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>

#include "brain_meshes.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "io/csv.hpp"
#include "io/plots.hpp"
#include "scale/child_process.hpp"
#include "scale/machine_bounds.hpp"
#include "scale/rate_search.hpp"
#include "scale/scale_model.hpp"

namespace roifem::bench {
namespace {

struct Options {
  std::vector<long> nodes{800, 5000, 20000};
  std::vector<std::string> rois{"300", "1000", "3%"};
  std::vector<long> haptic{};
  std::vector<long> full_cg{};  ///< sizes at which the full model also runs by trapezoid-cg
  long cg_check_steps = 20;
  std::vector<long> neo_hookean{};  ///< sizes at which the full model also runs with the neo-Hookean law
  double neo_hookean_load = 0.25;
  double haptic_rate_hz = 1000;
  std::filesystem::path out = "scale-results";
  TimingOptions timing;
  double model_timeout_s = 1800;
  bool machine_bounds = true;
};

/// "300" -> 300 nodes; "3%" -> 3% of the brain's nodes.
ModelSpec roi_spec(const std::string& text, long nodes) {
  const bool percent = !text.empty() && text.back() == '%';
  const double value = std::stod(percent ? text.substr(0, text.size() - 1) : text);
  const long count = percent ? std::lround(value / 100.0 * static_cast<double>(nodes)) : std::lround(value);
  if (!(count > 0)) throw InputError("--rois: '" + text + "' gives an empty ROI");
  return {"roi-" + text, count};
}

std::string row_text(long nodes, const std::string& label, const std::optional<ScaleMeasurement>& m,
                     const std::optional<ScaleMeasurement>& full, const std::string& failure) {
  if (!m) return format("%8ld %-10s  failed: %s", nodes, label.c_str(), failure.c_str());
  const double vs_full = full ? full->step_median_s / m->step_median_s : 0;
  std::string note;
  if (m->newton_per_step > 0)
    note =
        format("  Newton %.2f iterations/step; %ld steps from rest in %.1f s (%.1f s in Newton), %ld retried; peak |u| %.2f mm",
               m->newton_per_step, m->steps_timed, m->all_steps_s, m->factorization_s, m->retried_steps, m->peak_displacement_mm);
  if (m->cg_iterations_per_step > 0) {
    note = format("  CG %.0f iterations/step; ", m->cg_iterations_per_step);
    note += m->deviation_vs_direct >= 0 ? format("max |u_cg - u_direct| / max |u| = %.1e", m->deviation_vs_direct)
                                        : (m->check_note.empty() ? std::string("not checked") : m->check_note);
  }
  return format("%8ld %-10s %6ld %8ld %6ld %8.2f %9.2f %9.2f %8.2f %10.3f %10.3f %9.2f %8.0f %8s%s", nodes, label.c_str(),
                m->roi_nodes, m->system_dofs, m->interface_dofs, m->assembly_s, m->factorization_s, m->condensation_s,
                m->integrator_setup_s, m->step_median_s * 1e3, m->step_p99_s * 1e3, 1.0 / m->step_median_s, m->peak_rss_mb,
                full ? format("%.3gx", vs_full).c_str() : "-", note.c_str());
}

int run(const Options& o) {
  std::filesystem::create_directories(o.out);
  if (o.machine_bounds) report_machine_bounds(o.out);
  io::CsvWriter csv(o.out / "scale.csv",
                    "nodes,model,roi_nodes,system_dofs,interface_dofs,read_s,assembly_s,factorization_s,condensation_s,"
                    "integrator_setup_s,setup_s,step_median_ms,step_p99_ms,frame_rate_hz,steps_timed,peak_rss_mb,"
                    "step_vs_full,cg_iterations_per_step,cg_deviation_vs_direct,newton_per_step,all_steps_s,peak_displacement_mm,"
                    "retried_steps,status");
  std::printf(
      "Scale: trapezoidal rule, dt = 0.05 s; a step = new load + step + displacement out; medians over the timed steps\n");
  std::printf("%8s %-10s %6s %8s %6s %8s %9s %9s %8s %10s %10s %9s %8s %8s\n", "nodes", "model", "ROI", "dofs", "iface",
              "assem s", "factor s", "condens s", "K_eff s", "step ms", "p99 ms", "rate Hz", "peak MB", "vs full");
  for (long n : o.nodes) {
    const auto mesh_file = brain_mesh_file(n);
    std::vector<ModelSpec> models{{"full", 0}};
    if (std::find(o.full_cg.begin(), o.full_cg.end(), n) != o.full_cg.end())
      models.push_back({"full-cg", 0, true, o.cg_check_steps});
    if (std::find(o.neo_hookean.begin(), o.neo_hookean.end(), n) != o.neo_hookean.end())
      models.push_back({"full-nh", 0, false, 0, true, o.neo_hookean_load});
    for (const auto& r : o.rois)
      if (r != "none") models.push_back(roi_spec(r, n));
    std::optional<ScaleMeasurement> full;
    for (const auto& spec : models) {
      const bool direct_full =
          spec.roi_nodes == 0 && !spec.conjugate_gradients && !spec.neo_hookean;  // the row the others are compared with
      const ChildResult child =
          run_in_child([&] { return measure_model(mesh_file, spec, o.timing).serialize(); }, o.model_timeout_s);
      std::optional<ScaleMeasurement> m;
      if (child.ok) m = ScaleMeasurement::parse(child.output);
      if (direct_full) full = m;
      std::printf("%s\n", row_text(n, spec.label, m, direct_full ? std::nullopt : full, child.output).c_str());
      std::fflush(stdout);
      if (m)
        csv.row(format(
            "%ld,%s,%ld,%ld,%ld,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%ld,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%ld,ok",
            m->nodes, spec.label.c_str(), m->roi_nodes, m->system_dofs, m->interface_dofs, m->read_s, m->assembly_s,
            m->factorization_s, m->condensation_s, m->integrator_setup_s, m->setup_s(), m->step_median_s * 1e3,
            m->step_p99_s * 1e3, 1.0 / m->step_median_s, m->steps_timed, m->peak_rss_mb,
            full && !direct_full ? full->step_median_s / m->step_median_s : 1.0, m->cg_iterations_per_step,
            m->deviation_vs_direct, m->newton_per_step, m->all_steps_s, m->peak_displacement_mm, m->retried_steps));
      else
        csv.row(format("%ld,%s,,,,,,,,,,,,,,,,,,,,,,failed", n, spec.label.c_str()));
    }
  }
  csv.close();
  if (!o.haptic.empty()) {
    io::CsvWriter haptic(o.out / "haptic.csv", "nodes,rate_hz,roi_nodes,system_dofs,interface_dofs,step_median_ms,probes");
    std::printf("\nLargest ROI (nodes nearest the target) whose condensed step holds %.0f Hz (median <= %.3f ms):\n",
                o.haptic_rate_hz, 1e3 / o.haptic_rate_hz);
    for (long n : o.haptic) {
      const auto mesh_file = brain_mesh_file(n);
      // Each probe is a model of its own, in its own child with its own time limit: at 300k nodes
      // a probe factors for about 5 minutes and a search makes six or seven.
      const ChildResult counted = run_in_child([&] { return std::to_string(free_nodes(mesh_file)); }, o.model_timeout_s);
      if (!counted.ok) {
        std::printf("%8ld  failed: %s\n", n, counted.output.c_str());
        continue;
      }
      const RoiProbe probe = [&](long count) {
        const ChildResult child = run_in_child(
            [&] {
              return measure_model(mesh_file, {"roi-" + std::to_string(count), count}, o.timing).serialize();
            },
            o.model_timeout_s);
        if (!child.ok) {
          std::printf("         %ld nodes, ROI %ld: failed: %s\n", n, count, child.output.c_str());
          std::fflush(stdout);
          return ProbeResult{std::nullopt, child.output};
        }
        const ScaleMeasurement m = ScaleMeasurement::parse(child.output);
        std::printf("         %ld nodes, ROI %ld: step %.3f ms\n", m.nodes, count, m.step_median_s * 1e3);
        std::fflush(stdout);
        return ProbeResult{m, ""};
      };
      RateSearch r = largest_roi_at_rate(probe, 1.0 / o.haptic_rate_hz, std::stol(counted.output));
      if (r.nodes == 0) r.nodes = n;  // every probe failed: the mesh's own count is unknown here
      std::string probes;
      for (const auto& [count, result] : r.probes)
        probes += result.measurement ? format("%ld:%.3fms ", count, result.measurement->step_median_s * 1e3)
                                     : format("%ld:failed ", count);
      std::printf("%8ld nodes: ROI %ld nodes (%ld dofs, %ld on the interface), step %.3f ms   probes %s\n", r.nodes, r.roi_nodes,
                  r.system_dofs, r.interface_dofs, r.step_median_s * 1e3, probes.c_str());
      std::fflush(stdout);
      haptic.row(format("%ld,%.6g,%ld,%ld,%ld,%.6g,%s", r.nodes, o.haptic_rate_hz, r.roi_nodes, r.system_dofs, r.interface_dofs,
                        r.step_median_s * 1e3, probes.c_str()));
    }
    haptic.close();
  }
  io::run_plot_script("plot_scale.py", o.out, std::cerr);
  std::printf("\nwrote %s\n", (o.out / "scale.csv").c_str());
  return 0;
}

}  // namespace
}  // namespace roifem::bench

int main(int argc, char** argv) {
  using namespace roifem::bench;
  Options o;
  CLI::App app{
      "roifem scale benchmark: full and condensed brain models from 800 to 300k nodes, per-step time,\n"
      "setup time, memory, and the largest ROI at a haptic rate. Meshes are generated once and cached\n"
      "in $ROIFEM_MESH_CACHE (default ./bench-meshes)."};
  app.add_option("--nodes", o.nodes, "brain sizes (nodes)")->capture_default_str();
  app.add_option("--rois", o.rois, "condensed models: ROI sizes in nodes, a percentage of the brain's nodes, or none")
      ->capture_default_str();
  app.add_option("--haptic", o.haptic, "brain sizes at which to search the largest ROI that holds --rate")->capture_default_str();
  app.add_option("--full-cg", o.full_cg,
                 "brain sizes at which the full model also runs by trapezoid-cg (conjugate gradients, no factor: "
                 "for brains whose factor does not fit in memory)")
      ->capture_default_str();
  app.add_option("--cg-check-steps", o.cg_check_steps,
                 "steps over which trapezoid-cg is compared with the direct solve (where its factor fits; 0: no check)")
      ->capture_default_str();
  app.add_option("--neo-hookean", o.neo_hookean,
                 "brain sizes at which the full model also runs with the neo-Hookean law (same lambda, mu) by "
                 "Newton: --steps steps from rest, every one timed (row full-nh)")
      ->capture_default_str();
  app.add_option("--neo-hookean-load", o.neo_hookean_load,
                 "the neo-Hookean rows' wall forces, as a fraction of the paper's 16 mN (the full force opens a generated "
                 "brain's slit by centimetres and inverts elements)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--rate", o.haptic_rate_hz, "haptic rate (Hz)")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--out", o.out, "directory for scale.csv, haptic.csv and scale.png")->capture_default_str();
  app.add_option("--steps", o.timing.max_steps, "timed steps per model at most")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--step-budget", o.timing.step_budget_s, "seconds of timed steps per model (at least 10 steps)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--model-timeout", o.model_timeout_s, "seconds after which one model is stopped and its row marked failed")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_flag("!--no-machine-bounds", o.machine_bounds, "skip measuring the machine's bounds (smoke tests)");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roifem_scale_benchmark: %s\n", e.what());
    return 1;
  }
}
