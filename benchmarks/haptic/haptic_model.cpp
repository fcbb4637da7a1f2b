// SPDX-License-Identifier: GPL-3.0-or-later
#include "haptic/haptic_model.hpp"

#include <sys/mman.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "integrators/haptic_trapezoid.hpp"
#include "integrators/trapezoid.hpp"
#include "model/hyperelastic_force.hpp"
#include "roi/node_dofs.hpp"
#include "scale/brain_model.hpp"
#include "scale/child_process.hpp"
#include "simulation/run_loop.hpp"
#include "solvers/blas_threads.hpp"

namespace roifem::bench {

namespace {

/// Per-tick samples: wall time, and whether the thread was preempted or faulted during it.
struct TickSamples {
  std::vector<double> seconds;
  std::vector<char> preempted, faulted;
  void reserve(long n) {
    seconds.reserve(static_cast<std::size_t>(n));
    preempted.reserve(static_cast<std::size_t>(n));
    faulted.reserve(static_cast<std::size_t>(n));
  }
};

rusage thread_usage() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  return usage;
}

/// Runs `work` once, timed; the usage counters are read outside the timed interval.
template <class Work>
void timed(Work&& work, TickSamples& samples, bool record) {
  const rusage before = thread_usage();
  const Stopwatch clock;
  work();
  const double seconds = clock.seconds();
  const rusage after = thread_usage();
  if (!record) return;
  samples.seconds.push_back(seconds);
  samples.preempted.push_back(static_cast<char>(after.ru_nivcsw > before.ru_nivcsw));
  samples.faulted.push_back(static_cast<char>(after.ru_minflt + after.ru_majflt > before.ru_minflt + before.ru_majflt));
}

TickStats summarize(const TickSamples& s, double deadline_s) {
  TickStats t;
  t.median = simulation::median(s.seconds);
  t.p99 = simulation::percentile(s.seconds, 0.99);
  t.p999 = simulation::percentile(s.seconds, 0.999);
  t.max = *std::max_element(s.seconds.begin(), s.seconds.end());
  for (std::size_t k = 0; k < s.seconds.size(); ++k) {
    t.page_faults += s.faulted[k];
    t.preemptions += s.preempted[k];
    if (s.seconds[k] <= deadline_s) continue;
    ++t.late;
    t.late_preempted += s.preempted[k];
    t.late_page_fault += s.faulted[k];
  }
  return t;
}

/// The surgeon's hand: 2 mm outwards (x) over 0.5 s on a smooth ramp, with a 0.3 mm circle at 3 Hz
/// in x and y on top (a hand is never still).
Vec3 hand(double t) {
  const double s = std::min(t / 0.5, 1.0), ramp = s * s * s * (10 - 15 * s + 6 * s * s);
  const double w = 2 * std::numbers::pi * 3;
  return {2e-3 * ramp + 0.3e-3 * std::sin(w * t), 0.3e-3 * (1 - std::cos(w * t)), 0.0};
}

/// The ROI's nodes of the right wall nearest the target, `count` at most, as dofs of the condensed
/// system (the ROI's own dofs come first there).
std::vector<std::array<Index, 3>> tool_dofs(const Brain& brain, const condensation::ReducedModel& reduced, long count) {
  const auto& roi_nodes = reduced.partition().roi_nodes;
  std::vector<int> wall;
  for (int n : brain.mesh.set("opening_right").nodes)
    if (std::binary_search(roi_nodes.begin(), roi_nodes.end(), n)) wall.push_back(n);
  const Vec3 target = nearest_target(1).center;
  std::sort(wall.begin(), wall.end(), [&](int a, int b) {
    return (brain.mesh.node(a) - target).squaredNorm() < (brain.mesh.node(b) - target).squaredNorm();
  });
  wall.resize(std::min(wall.size(), static_cast<std::size_t>(count)));
  if (wall.empty()) throw ModelError("haptic benchmark: the ROI holds no node of the right wall");
  std::sort(wall.begin(), wall.end());
  const roi::NodeDofs dofs = roi::node_dofs_in_reduced(wall, reduced.partition(), *brain.model.dofs);
  for (const auto& d : dofs)
    if (d[0] < 0 || d[1] < 0 || d[2] < 0) throw ModelError("haptic benchmark: a wall node is partly fixed");
  return dofs;
}

/// The machine's own jitter at the tick's length and memory traffic: reads `bytes` (about the
/// condensed factor's dense block, which a solve reads twice), as many passes as take about
/// `seconds`; no solver, no BLAS, no allocation.
class Control {
 public:
  Control(double seconds, std::size_t bytes) : data_(std::max<std::size_t>(bytes / sizeof(double), 1 << 17), 1.0) {
    auto median_of_runs = [this] {
      std::vector<double> times;
      for (int k = 0; k < 9; ++k) {
        const Stopwatch clock;
        run();
        times.push_back(clock.seconds());
      }
      return simulation::median(times);
    };
    for (int round = 0; round < 3; ++round)
      passes_ = std::max(1L, std::lround(static_cast<double>(passes_) * seconds / median_of_runs()));
  }
  void run() {
    double sum = 0;
    for (long pass = 0; pass < passes_; ++pass)
      for (const double x : data_) sum += x;
    sink_ = sum;
  }

 private:
  std::vector<double> data_;
  long passes_ = 1;
  volatile double sink_ = 0;
};

}  // namespace

std::string TickStats::serialize(const std::string& p) const {
  std::ostringstream out;
  out.precision(17);
  out << p << "median=" << median << "\n"
      << p << "p99=" << p99 << "\n"
      << p << "p999=" << p999 << "\n"
      << p << "max=" << max << "\n"
      << p << "late=" << late << "\n"
      << p << "late_preempted=" << late_preempted << "\n"
      << p << "late_page_fault=" << late_page_fault << "\n"
      << p << "page_faults=" << page_faults << "\n"
      << p << "preemptions=" << preemptions << "\n";
  return out.str();
}

TickStats TickStats::parse(const std::string& text, const std::string& p) {
  const auto f = parse_key_values(text);
  TickStats t;
  t.median = std::stod(f.at(p + "median"));
  t.p99 = std::stod(f.at(p + "p99"));
  t.p999 = std::stod(f.at(p + "p999"));
  t.max = std::stod(f.at(p + "max"));
  t.late = std::stol(f.at(p + "late"));
  t.late_preempted = std::stol(f.at(p + "late_preempted"));
  t.late_page_fault = std::stol(f.at(p + "late_page_fault"));
  t.page_faults = std::stol(f.at(p + "page_faults"));
  t.preemptions = std::stol(f.at(p + "preemptions"));
  return t;
}

std::string HapticMeasurement::serialize() const {
  std::ostringstream out;
  out.precision(17);
  out << "nodes=" << nodes << "\nroi_nodes=" << roi_nodes << "\nsystem_dofs=" << system_dofs
      << "\ninterface_dofs=" << interface_dofs << "\ntool_nodes=" << tool_nodes << "\nsetup_s=" << setup_s
      << "\nattach_s=" << attach_s << "\npeak_force_N=" << peak_force_N << "\nmemory_locked=" << memory_locked
      << "\nblas_threads=" << blas_threads << "\nnewton_iterations=" << newton_iterations
      << "\nnewton_residual=" << newton_residual << "\nforce_error_rel=" << force_error_rel
      << "\nnonlinear_ticks=" << nonlinear_ticks << "\n";
  return out.str() + plain.serialize("plain_") + haptic.serialize("haptic_") + control.serialize("control_") +
         nonlinear.serialize("nonlinear_");
}

HapticMeasurement HapticMeasurement::parse(const std::string& text) {
  const auto f = parse_key_values(text);
  HapticMeasurement m;
  m.nodes = std::stol(f.at("nodes"));
  m.roi_nodes = std::stol(f.at("roi_nodes"));
  m.system_dofs = std::stol(f.at("system_dofs"));
  m.interface_dofs = std::stol(f.at("interface_dofs"));
  m.tool_nodes = std::stol(f.at("tool_nodes"));
  m.setup_s = std::stod(f.at("setup_s"));
  m.attach_s = std::stod(f.at("attach_s"));
  m.peak_force_N = std::stod(f.at("peak_force_N"));
  m.memory_locked = f.at("memory_locked") == "1";
  m.blas_threads = std::stoi(f.at("blas_threads"));
  m.plain = TickStats::parse(text, "plain_");
  m.haptic = TickStats::parse(text, "haptic_");
  m.control = TickStats::parse(text, "control_");
  m.nonlinear = TickStats::parse(text, "nonlinear_");
  m.newton_iterations = std::stoi(f.at("newton_iterations"));
  m.newton_residual = std::stod(f.at("newton_residual"));
  m.force_error_rel = std::stod(f.at("force_error_rel"));
  m.nonlinear_ticks = std::stol(f.at("nonlinear_ticks"));
  return m;
}

HapticMeasurement measure_haptic(const std::filesystem::path& mesh_file, Index roi_nodes, const HapticOptions& o) {
  const solvers::BlasThreadsScope blas(o.blas_threads > 0 ? o.blas_threads : solvers::BlasThreadsScope::unchanged);
  const auto brain = build_brain(mesh_file);
  HapticMeasurement m;
  m.nodes = static_cast<long>(brain->mesh.num_nodes());
  m.blas_threads = solvers::BlasThreadsScope::current();
  const Stopwatch setup;
  const Condensed condensed = condense(*brain, roi_nodes);
  const model::SecondOrderSystem& system = condensed.condensation->system();
  m.roi_nodes = static_cast<long>(condensed.condensation->partition().roi_nodes.size());
  m.system_dofs = static_cast<long>(system.size());
  m.interface_dofs = condensed.interface_dofs;
  const double dt = 1.0 / o.rate_hz;
  integrators::Trapezoid plain(dt);
  model::State plain_state = model::State::at_rest(system.size()), haptic_state = plain_state;
  plain.reset(system, plain_state);
  integrators::HapticTrapezoid haptic(system, dt);
  m.setup_s = setup.seconds();
  const auto held = tool_dofs(*brain, *condensed.condensation, o.tool_nodes);
  m.tool_nodes = static_cast<long>(held.size());
  haptic.attach(held);
  haptic.reset(haptic_state);
  m.attach_s = haptic.attach_seconds();
  // The hybrid ROI: the same condensation, its elements with no node in the static part neo-Hookean;
  // ticked with the budget, and once more to convergence (untimed) for the force error.
  const int budget = o.newton_iterations;
  // The tool alone drives it: the brain's own wall forces (the paper's 16 mN, which open the 20k
  // brain's slit by 24 mm and invert elements under the law) are left out.
  model::SecondOrderSystem hybrid = system;
  hybrid.load = model::LoadHistory(system.size());
  std::unique_ptr<integrators::HapticTrapezoid> nonlinear, converged;
  model::State nonlinear_state = haptic_state, converged_state = haptic_state;
  if (budget > 0) {
    const fem::MaterialMap law = brain->model.materials.mapped([](fem::Material material) {
      material.model = fem::MaterialModel::neo_hookean;
      return material;
    });
    hybrid.internal_force = model::hybrid_roi_force(brain->mesh, *brain->model.dofs, law, fem::Element::tet4,
                                                    condensed.condensation->partition(), system.K, {}, &system.K_split);
    nonlinear = std::make_unique<integrators::HapticTrapezoid>(hybrid, dt, integrators::HapticNewton{.iterations = budget});
    converged = std::make_unique<integrators::HapticTrapezoid>(hybrid, dt,
                                                               integrators::HapticNewton{.iterations = 100, .tolerance = 1e-12});
    for (auto* h : {nonlinear.get(), converged.get()}) h->attach(held);
    nonlinear->reset(nonlinear_state);
    converged->reset(converged_state);
    m.newton_iterations = budget;
  }
  if (o.lock_memory) m.memory_locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;

  Vector displacement_out(system.size());
  Vec3 force_out = Vec3::Zero();
  TickSamples plain_ticks, haptic_ticks, control_ticks, nonlinear_ticks;
  for (auto* s : {&plain_ticks, &haptic_ticks, &control_ticks, &nonlinear_ticks}) s->reserve(o.ticks);
  // The budgeted ticks of a block run back to back, as the linear ones do; the converged run (its
  // own factor, its own trajectory under the same hand) follows, untimed, so that it never evicts
  // the budgeted tick's factor from the cache between two ticks.
  std::vector<Vec3> nonlinear_forces;
  nonlinear_forces.reserve(500);
  double peak_converged = 0, force_error = 0;
  auto nonlinear_tick = [&] {
    nonlinear_forces.push_back(nonlinear->tick(o.hand_scale * hand(nonlinear_state.t + dt), nonlinear_state));
    displacement_out = nonlinear_state.u;
  };
  auto compare_with_converged = [&](const Vec3& budgeted) {  // untimed
    const Vec3 exact = converged->tick(o.hand_scale * hand(converged_state.t + dt), converged_state);
    peak_converged = std::max(peak_converged, exact.norm());
    force_error = std::max(force_error, (budgeted - exact).norm());
  };
  auto plain_step = [&] {
    plain.step(plain_state);
    displacement_out = plain_state.u;
  };
  auto haptic_tick = [&] {
    force_out = haptic.tick(hand(haptic_state.t + dt), haptic_state);
    displacement_out = haptic_state.u;
  };
  // The nonlinear run may stop (an element inverted, a diverging iteration): its ticks so far are
  // kept and the linear measurement goes on.
  bool nonlinear_running = budget > 0;
  auto nonlinear_block = [&](long count, bool record) {
    const char* which = "the budgeted tick";
    try {
      nonlinear_forces.clear();
      for (long k = 0; k < count && nonlinear_running; ++k) {
        timed(nonlinear_tick, nonlinear_ticks, record);
        m.newton_residual = std::max(m.newton_residual, nonlinear->last_residual());
      }
      which = "the converged tick";
      for (const Vec3& budgeted : nonlinear_forces) compare_with_converged(budgeted);
      if (record) m.nonlinear_ticks += static_cast<long>(nonlinear_forces.size());
    } catch (const Error& e) {
      nonlinear_running = false;
      std::fprintf(stderr, "nonlinear tick stopped after %ld timed ticks, in %s at t = %.4f s: %s\n", m.nonlinear_ticks, which,
                   nonlinear_state.t, e.what());
    }
  };
  for (long k = 0; k < o.warmup; ++k) {
    timed(plain_step, plain_ticks, false);
    timed(haptic_tick, haptic_ticks, false);
    nonlinear_block(1, false);
  }
  const auto interface_dofs = static_cast<std::size_t>(condensed.interface_dofs);
  Control control(simulation::median([&] {
                    TickSamples probe;
                    for (int k = 0; k < 50; ++k) timed(plain_step, probe, true);
                    return probe.seconds;
                  }()),
                  interface_dofs * interface_dofs * sizeof(double) / 2);
  constexpr long block = 500;  // ticks of each in turn
  for (long done = 0; done < o.ticks; done += block) {
    const long count = std::min(block, o.ticks - done);
    for (long k = 0; k < count; ++k) timed(plain_step, plain_ticks, true);
    for (long k = 0; k < count; ++k) {
      timed(haptic_tick, haptic_ticks, true);
      m.peak_force_N = std::max(m.peak_force_N, force_out.norm());
    }
    nonlinear_block(count, true);
    for (long k = 0; k < count; ++k) timed([&] { control.run(); }, control_ticks, true);
  }
  if (!haptic_state.u.allFinite()) throw SolverError("haptic benchmark: the haptic run diverged");
  m.plain = summarize(plain_ticks, dt);
  m.haptic = summarize(haptic_ticks, dt);
  m.control = summarize(control_ticks, dt);
  if (budget > 0 && !nonlinear_ticks.seconds.empty()) {
    m.nonlinear = summarize(nonlinear_ticks, dt);
    m.force_error_rel = force_error / peak_converged;
  }
  return m;
}

}  // namespace roifem::bench
