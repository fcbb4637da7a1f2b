// SPDX-License-Identifier: GPL-3.0-or-later
#include "scale/scale_model.hpp"

#include <algorithm>
#include <limits>
#include <memory>
#include <sstream>

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "condensation/reduced_model.hpp"
#include "integrators/trapezoid.hpp"
#include "model/fem_model.hpp"
#include "scale/brain_model.hpp"
#include "scale/child_process.hpp"
#include "simulation/run_loop.hpp"

namespace roifem::bench {

namespace {

constexpr double dt = 0.05;  // the paper's step

/// Median and p99 of the per-tick time: load, step, displacement out.
/// `peak_u`, where given: the largest |u_i| over the steps.
std::pair<double, double> time_steps(const model::SecondOrderSystem& system, integrators::Trapezoid& trapezoid,
                                     const TimingOptions& timing, long& steps_timed, double* peak_u = nullptr) {
  model::State state = model::State::at_rest(system.size());
  trapezoid.reset(system, state);
  Vector out(system.size());
  std::vector<double> seconds;
  long target = timing.max_steps;
  for (long k = 0; k < timing.warmup_steps + target; ++k) {
    const Stopwatch clock;
    trapezoid.step(state);
    out = state.u;
    const double s = clock.seconds();
    if (peak_u) *peak_u = std::max(*peak_u, state.u.lpNorm<Eigen::Infinity>());
    if (k < timing.warmup_steps) {
      target = std::clamp(static_cast<long>(timing.step_budget_s / s), std::min(10L, timing.max_steps), timing.max_steps);
      continue;
    }
    seconds.push_back(s);
  }
  steps_timed = static_cast<long>(seconds.size());
  return {simulation::median(seconds), simulation::percentile(seconds, 0.99)};
}

/// trapezoid-cg against the direct solve, in lockstep from rest (after the timing, so that the
/// direct factor's memory is not counted in the measured peak).
void check_against_direct(const model::SecondOrderSystem& system, long steps, ScaleMeasurement& m) {
  integrators::Trapezoid direct(dt), cg(dt, solvers::CgSettings{});
  model::State a = model::State::at_rest(system.size()), b = a;
  try {
    direct.reset(system, a);
  } catch (const std::exception& e) {
    m.check_note = std::string("direct solve unavailable: ") + e.what();
    std::replace(m.check_note.begin(), m.check_note.end(), '\n', ' ');  // one key=value line
    return;
  }
  cg.reset(system, b);
  double worst = 0, peak = 0;
  for (long k = 0; k < steps; ++k) {
    direct.step(a);
    cg.step(b);
    peak = std::max(peak, a.u.norm());
    worst = std::max(worst, (b.u - a.u).norm());
  }
  m.deviation_vs_direct = worst / peak;
}

}  // namespace

std::string ScaleMeasurement::serialize() const {
  std::ostringstream out;
  out.precision(17);
  out << "nodes=" << nodes << "\ndofs=" << dofs << "\nroi_nodes=" << roi_nodes << "\nsystem_dofs=" << system_dofs
      << "\ninterface_dofs=" << interface_dofs << "\nread_s=" << read_s << "\nassembly_s=" << assembly_s
      << "\nfactorization_s=" << factorization_s << "\ncondensation_s=" << condensation_s
      << "\nintegrator_setup_s=" << integrator_setup_s << "\nstep_median_s=" << step_median_s << "\nstep_p99_s=" << step_p99_s
      << "\nsteps_timed=" << steps_timed << "\npeak_rss_mb=" << peak_rss_mb
      << "\ncg_iterations_per_step=" << cg_iterations_per_step << "\ndeviation_vs_direct=" << deviation_vs_direct
      << "\ncheck_note=" << check_note << "\nnewton_per_step=" << newton_per_step << "\nall_steps_s=" << all_steps_s
      << "\npeak_displacement_mm=" << peak_displacement_mm << "\nretried_steps=" << retried_steps << "\n";
  return out.str();
}

ScaleMeasurement ScaleMeasurement::parse(const std::string& text) {
  auto f = parse_key_values(text);
  ScaleMeasurement m;
  m.nodes = std::stol(f.at("nodes"));
  m.dofs = std::stol(f.at("dofs"));
  m.roi_nodes = std::stol(f.at("roi_nodes"));
  m.system_dofs = std::stol(f.at("system_dofs"));
  m.interface_dofs = std::stol(f.at("interface_dofs"));
  m.read_s = std::stod(f.at("read_s"));
  m.assembly_s = std::stod(f.at("assembly_s"));
  m.factorization_s = std::stod(f.at("factorization_s"));
  m.condensation_s = std::stod(f.at("condensation_s"));
  m.integrator_setup_s = std::stod(f.at("integrator_setup_s"));
  m.step_median_s = std::stod(f.at("step_median_s"));
  m.step_p99_s = std::stod(f.at("step_p99_s"));
  m.steps_timed = std::stol(f.at("steps_timed"));
  m.peak_rss_mb = std::stod(f.at("peak_rss_mb"));
  m.cg_iterations_per_step = std::stod(f.at("cg_iterations_per_step"));
  m.deviation_vs_direct = std::stod(f.at("deviation_vs_direct"));
  m.check_note = f.at("check_note");
  m.newton_per_step = std::stod(f.at("newton_per_step"));
  m.all_steps_s = std::stod(f.at("all_steps_s"));
  m.peak_displacement_mm = std::stod(f.at("peak_displacement_mm"));
  m.retried_steps = std::stol(f.at("retried_steps"));
  return m;
}

ScaleMeasurement measure_model(const std::filesystem::path& mesh_file, const ModelSpec& spec, const TimingOptions& timing) {
  const auto brain =
      build_brain(mesh_file, spec.neo_hookean ? fem::MaterialModel::neo_hookean : fem::MaterialModel::linear, spec.load_scale);
  ScaleMeasurement m;
  m.nodes = static_cast<long>(brain->mesh.num_nodes());
  m.dofs = static_cast<long>(brain->model.system.size());
  m.read_s = brain->read_s;
  m.assembly_s = brain->assembly_s;
  integrators::Trapezoid trapezoid =
      spec.conjugate_gradients ? integrators::Trapezoid(dt, solvers::CgSettings{}) : integrators::Trapezoid(dt);
  const model::SecondOrderSystem* system = &brain->model.system;
  Condensed condensed;
  if (spec.roi_nodes > 0) {
    condensed = condense(*brain, spec.roi_nodes);
    const auto& t = condensed.condensation->timings();
    m.factorization_s = t.factorization_s;
    m.condensation_s = t.interface_solve_s + t.assembly_s;
    m.roi_nodes = static_cast<long>(condensed.condensation->partition().roi_nodes.size());
    m.interface_dofs = condensed.interface_dofs;
    system = &condensed.condensation->system();
  }
  m.system_dofs = static_cast<long>(system->size());
  TimingOptions options = timing;
  if (spec.neo_hookean) {  // every step from rest: a nonlinear step's cost grows with the load
    options.warmup_steps = 0;
    options.step_budget_s = std::numeric_limits<double>::infinity();
  }
  double peak_u = 0;
  const Stopwatch all;
  const auto [median, p99] = time_steps(*system, trapezoid, options, m.steps_timed, spec.neo_hookean ? &peak_u : nullptr);
  const integrators::Stats stats = trapezoid.stats();
  (spec.roi_nodes > 0 ? m.integrator_setup_s : m.factorization_s) = stats.factorization_s;
  m.step_median_s = median;
  m.step_p99_s = p99;
  m.peak_rss_mb = peak_rss_mb();
  if (spec.neo_hookean) {
    m.all_steps_s = all.seconds();
    m.newton_per_step = static_cast<double>(stats.nonlinear_iterations) / static_cast<double>(m.steps_timed);
    m.peak_displacement_mm = peak_u / mm;
    m.retried_steps = stats.failed_steps;
  }
  if (spec.conjugate_gradients) {
    m.cg_iterations_per_step = static_cast<double>(stats.lin_iterations) / static_cast<double>(stats.steps);
    if (spec.check_steps > 0) check_against_direct(*system, spec.check_steps, m);
  }
  return m;
}

long free_nodes(const std::filesystem::path& mesh_file) {
  return static_cast<long>(build_brain(mesh_file)->model.system.size() / 3);  // an upper bound on ROI sizes worth probing
}

}  // namespace roifem::bench
