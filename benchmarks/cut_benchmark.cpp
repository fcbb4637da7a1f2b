// SPDX-License-Identifier: GPL-3.0-or-later
// Cut: what removing tetrahedra inside the ROI costs the trapezoidal rule on condensed brains, at
// the haptic tick's step (dt = 1 ms). Per brain and ROI (each in its own child process), for cuts
// of 1, 10 and 100 tetrahedra nearest the surgical target: forming the change (the removed
// elements' blocks and the nodes they orphan, fem/element_removal.hpp's ElementRemover), taking it into the factor of K_eff by
// Woodbury's correction (solvers/low_rank_update.hpp: Z = K_eff^-1 U in one multi-column solve and the capacitance), a solve
// after it against a solve before (medians of 51; the others of 5), and the alternatives: a numeric refactorization of the
// changed K_eff (its pattern analysed beforehand) and the whole condensation that a cut touching the static part would need. The
// corrected solve is checked against the refactorized one (gap: |x - x_refactored| / |x|). Then the haptic loop (a tool on 10
// wall nodes, integrators/haptic_trapezoid.hpp): the cut taken between two ticks (the factor's
// correction and the compliance's: the event, and the ticks of 1 ms it spans), and the tick's
// median before and after. Then split mode (measure_split below). Writes DIR/cut.csv and DIR/split.csv.
//   compile with: cmake --build --preset release --target roifem_cut_benchmark
//   sample run:   build/release/benchmarks/roifem_cut_benchmark --nodes 20000 100000 --rois 300 1000 --out results/cut
#include <CLI/CLI.hpp>

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <thread>

#include "brain_meshes.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/timer.hpp"
#include "cutting/blade.hpp"
#include "fem/element_removal.hpp"
#include "integrators/haptic_trapezoid.hpp"
#include "io/csv.hpp"
#include "model/average_acceleration.hpp"
#include "scale/brain_model.hpp"
#include "scale/child_process.hpp"
#include "scale/machine_bounds.hpp"
#include "scenario/scenario.hpp"
#include "simulation/run_loop.hpp"
#include "simulation/scenario_stepper.hpp"
#include "solvers/blas_threads.hpp"
#include "solvers/cholesky.hpp"
#include "solvers/low_rank_update.hpp"

namespace roifem::bench {
namespace {

struct Options {
  std::vector<long> nodes{20000, 100000};
  std::vector<long> rois{300, 1000};
  std::vector<long> cuts{1, 10, 100};
  std::vector<double> split_sizes{2, 4, 8};
  long blade_ticks = 4000;     ///< the blade-in-the-loop run (0: skip)
  double blade_speed = 0.005;  ///< m/s
  std::filesystem::path out = "cut-results";
  double model_timeout_s = 1800;
  bool machine_bounds = true;
  bool cut_table = true;  ///< the cut events' table (cut.csv)
};

/// The haptic tool: the ROI's nodes of the right wall nearest the target (as the haptic benchmark's).
std::vector<int> tool_nodes(const Brain& brain, const roi::Partition& partition, std::size_t count) {
  std::vector<int> wall;
  for (const int n : brain.mesh.set("opening_right").nodes)
    if (std::binary_search(partition.roi_nodes.begin(), partition.roi_nodes.end(), n)) wall.push_back(n);
  const Vec3 target(0, 0, 0.040);
  std::sort(wall.begin(), wall.end(), [&](int a, int b) {
    return (brain.mesh.node(a) - target).squaredNorm() < (brain.mesh.node(b) - target).squaredNorm();
  });
  wall.resize(std::min(wall.size(), count));
  return wall;
}

/// Per free dof of the brain's full model, its unknown in the condensed system (-1: the static part's).
std::vector<Index> roi_positions(const Brain& brain, const roi::Partition& partition) {
  std::vector<Index> position(static_cast<std::size_t>(brain.model.dofs->num_free()), -1);
  for (std::size_t i = 0; i < partition.d.size(); ++i) position[static_cast<std::size_t>(partition.d[i])] = static_cast<Index>(i);
  return position;
}

/// The tool's nodes' unknowns in the condensed system.
std::vector<std::array<Index, 3>> held_dofs(const Brain& brain, const std::vector<Index>& position,
                                            const std::vector<int>& tool) {
  std::vector<std::array<Index, 3>> held;
  for (const int node : tool) {
    std::array<Index, 3> d{};
    for (int component = 0; component < 3; ++component)
      d[static_cast<std::size_t>(component)] = position[static_cast<std::size_t>(brain.model.dofs->free_dof(node, component))];
    held.push_back(d);
  }
  return held;
}

/// Takes a removal into the haptic loop between two ticks: the change in `system`'s numbering, the
/// held dofs set at rest, the system changed in place, the loop's factor and compliance corrected.
/// With `prefetch_s`: the change's columns solved first (as the look-ahead would have, earlier), timed.
void cut_haptic(integrators::HapticTrapezoid& loop, model::SecondOrderSystem& system, model::State& state,
                const fem::ElementRemoval& removal, const fem::DofMap& dofs, const std::vector<Index>& position,
                double* prefetch_s = nullptr) {
  model::SystemChange change = model::SystemChange::from_removal(removal, dofs, position, system.load.terms().size());
  if (prefetch_s) {
    const Stopwatch clock;
    loop.prefetch_change(change.dofs);
    *prefetch_s = clock.seconds();
  }
  for (const Index d : change.held) state.v[d] = 0;
  change.apply(system);
  loop.take_change(change, state);
}

/// The ROI's tetrahedra (every node in the ROI or fixed) clear of the tool's nodes, nearest the target first.
std::vector<Index> roi_tetrahedra(const Brain& brain, const roi::Partition& partition, const std::vector<int>& tool) {
  const fem::DofMap& dofs = *brain.model.dofs;
  std::vector<bool> movable(static_cast<std::size_t>(brain.mesh.num_nodes()), false);
  for (const Index d : partition.s) movable[static_cast<std::size_t>(dofs.full_dof(d) / 3)] = true;  // the static part's
  for (const int n : tool) movable[static_cast<std::size_t>(n)] = true;
  std::vector<std::pair<double, Index>> near;
  const Vec3 target(0, 0, 0.040);
  for (Index e = 0; e < brain.mesh.num_tets(); ++e) {
    const auto& t = brain.mesh.tets[static_cast<std::size_t>(e)];
    if (std::any_of(t.begin(), t.end(), [&](int n) { return movable[static_cast<std::size_t>(n)]; })) continue;
    Vec3 centre = Vec3::Zero();
    for (const int n : t) centre += brain.mesh.node(n) / 4;
    near.emplace_back((centre - target).norm(), e);
  }
  std::sort(near.begin(), near.end());
  std::vector<Index> out;
  for (const auto& [distance, e] : near) out.push_back(e);
  return out;
}

template <class F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> s;
  for (int i = 0; i < repeats; ++i) {
    const Stopwatch clock;
    f();
    s.push_back(clock.seconds());
  }
  return simulation::median(s);
}

/// The child's work: one line per cut size, "table<TAB>csv".
std::string measure(const std::filesystem::path& mesh_file, long roi_nodes, const std::vector<long>& cuts) {
  const auto brain = build_brain(mesh_file);
  const Stopwatch condense_clock;
  const Condensed condensed = condense(*brain, roi_nodes);
  const double condense_s = condense_clock.seconds();
  const model::SecondOrderSystem& system = condensed.condensation->system();
  const roi::Partition& partition = condensed.condensation->partition();
  const model::AverageAcceleration rule(1e-3);
  const double c = rule.mass_factor(system.damping);
  const SparseMatrix K_eff = rule.effective_stiffness(system);
  const std::vector<Index> last = system.dense_block_dofs();
  solvers::Cholesky factor;
  factor.compute(K_eff, last);
  const Index n = system.size();
  const std::vector<Index> position = roi_positions(*brain, partition);
  const std::vector<int> tool = tool_nodes(*brain, partition, 10);
  const std::vector<Index> tetrahedra = roi_tetrahedra(*brain, partition, tool);
  const std::vector<std::array<Index, 3>> held = held_dofs(*brain, position, tool);
  const auto hand = [](long tick) { return Vec3(0.001 * std::min(static_cast<double>(tick) / 50.0, 1.0), 0, 0); };

  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Vector b(n), x(n), x_after(n), x_refactored(n);
  for (Index i = 0; i < n; ++i) b[i] = uniform(random);
  const double solve_s = median_seconds(51, [&] { factor.solve(b, x); });
  std::string lines;
  for (const long k : cuts) {
    if (static_cast<std::size_t>(k) > tetrahedra.size()) continue;
    const std::vector<Index> removed(tetrahedra.begin(), tetrahedra.begin() + k);
    // Forming it: fem::ElementRemover keeps which tetrahedra meet at each node, so a removal costs its own.
    const fem::ElementRemover uncut(brain->mesh, *brain->model.dofs, brain->model.materials);
    fem::ElementRemoval removal;
    std::vector<double> form_times;
    for (int i = 0; i < 5; ++i) {
      fem::ElementRemover remover = uncut;
      const Stopwatch clock;
      removal = remover.remove(removed, c);
      form_times.push_back(clock.seconds());
    }
    const double form_s = simulation::median(form_times);
    std::vector<Index> dofs;
    for (const Index d : removal.dofs) dofs.push_back(position[static_cast<std::size_t>(d)]);
    const auto make_update = [&] {
      return solvers::LowRankUpdate([&](const Vector& rhs, Vector& out) { factor.solve(rhs, out); }, n,
                                    [&](const DenseMatrix& B) { return factor.solve_matrix(B); });
    };
    solvers::LowRankUpdate update = make_update();
    const double update_s = median_seconds(5, [&] {
      update = make_update();
      update.add(dofs, removal.change);
    });
    const double after_s = median_seconds(51, [&] { update.solve(b, x_after); });
    // The alternative: K_eff changed and factorized again (its pattern analysed beforehand, untimed).
    std::vector<Eigen::Triplet<double, Index>> entries;
    for (std::size_t i = 0; i < dofs.size(); ++i)
      for (std::size_t j = 0; j < dofs.size(); ++j)
        entries.emplace_back(dofs[i], dofs[j], removal.change(static_cast<Index>(i), static_cast<Index>(j)));
    SparseMatrix K_change(n, n);
    K_change.setFromTriplets(entries.begin(), entries.end());
    const SparseMatrix K_changed = K_eff + K_change;
    solvers::Cholesky refactored;
    refactored.analyze(K_changed, last);
    const double refactor_s = median_seconds(5, [&] { refactored.factorize(K_changed); });
    refactored.solve(b, x_refactored);
    const double gap = (x_after - x_refactored).norm() / x_refactored.norm();

    // The haptic loop: the same cut taken between two ticks (HapticTrapezoid::take_change), on a
    // copy of the system that the cut changes: the event's cost, and the tick before and after.
    model::SecondOrderSystem cut_system = system;
    integrators::HapticTrapezoid haptic(cut_system, rule.dt());
    haptic.attach(held);
    model::State state = model::State::at_rest(n);
    haptic.reset(state);
    long tick = 0;
    const double tick_before_s = median_seconds(51, [&] { haptic.tick(hand(++tick), state); });
    fem::ElementRemover remover = uncut;
    const fem::ElementRemoval stiffness_change = remover.remove(removed, 0.0);
    cut_haptic(haptic, cut_system, state, stiffness_change, *brain->model.dofs, position);
    const double event_s = haptic.change_seconds();
    const double tick_after_s = median_seconds(51, [&] { haptic.tick(hand(++tick), state); });
    // The same cut with its columns K_eff^-1 e_d solved ahead (between earlier ticks, as a blade
    // approaches: HapticTrapezoid::prefetch_change), on a second loop: the look-ahead's cost, and the event.
    model::SecondOrderSystem ahead_system = system;
    integrators::HapticTrapezoid ahead(ahead_system, rule.dt());
    ahead.attach(held);
    model::State ahead_state = model::State::at_rest(n);
    ahead.reset(ahead_state);
    for (long i = 1; i <= 51; ++i) ahead.tick(hand(i), ahead_state);
    double prefetch_s = 0;
    cut_haptic(ahead, ahead_system, ahead_state, stiffness_change, *brain->model.dofs, position, &prefetch_s);
    const double ahead_event_s = ahead.change_seconds();
    lines +=
        format(
            "%8lld %5ld %6lld %6ld %5ld %5lld %8.3f %9.2f %8.3f %8.3f %10.1f %9.2f  %.1e | %8.2f %5.0f %7.3f %7.3f | %8.2f "
            "%8.2f %5.0f\t",
            static_cast<long long>(brain->mesh.num_nodes()), roi_nodes, static_cast<long long>(n), condensed.interface_dofs, k,
            static_cast<long long>(dofs.size()), form_s * 1e3, update_s * 1e3, solve_s * 1e3, after_s * 1e3, refactor_s * 1e3,
            condense_s, gap, event_s * 1e3, std::ceil(event_s / rule.dt()), tick_before_s * 1e3, tick_after_s * 1e3,
            prefetch_s * 1e3, ahead_event_s * 1e3, std::ceil(ahead_event_s / rule.dt())) +
        format("%lld,%ld,%lld,%ld,%ld,%lld,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.3g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
               static_cast<long long>(brain->mesh.num_nodes()), roi_nodes, static_cast<long long>(n), condensed.interface_dofs, k,
               static_cast<long long>(dofs.size()), form_s * 1e3, update_s * 1e3, solve_s * 1e3, after_s * 1e3, refactor_s * 1e3,
               condense_s, gap, event_s * 1e3, tick_before_s * 1e3, tick_after_s * 1e3, prefetch_s * 1e3, ahead_event_s * 1e3);
  }
  return lines;
}

/// Tick statistics over a loop's timed ticks: "median p99 max (ms) late per 10,000".
struct LoopTicks {
  double median = 0, p99 = 0, max = 0, late_per_10k = 0;
};

LoopTicks loop_ticks(const std::vector<double>& seconds, double deadline) {
  LoopTicks t;
  t.median = simulation::median(seconds);
  t.p99 = simulation::percentile(seconds, 0.99);
  t.max = *std::max_element(seconds.begin(), seconds.end());
  t.late_per_10k = 1e4 *
                   static_cast<double>(std::count_if(seconds.begin(), seconds.end(), [&](double s) { return s > deadline; })) /
                   static_cast<double>(seconds.size());
  return t;
}

/// A blade cutting while the haptic loop runs: its edge 8 mm long beside the opening, swept down
/// through the target's depth at `speed` (m/s), removing the tetrahedra it crosses (those at the
/// static part or the tool skipped, and counted) at the tick it reaches them. Each tick, the cut
/// due (the removal formed and taken: HapticTrapezoid::take_change), the tick itself, and, where a
/// column still ends within 90% of dt, the columns K_eff^-1 e_d of the next tetrahedra the blade
/// will reach (within 0.5 s), one at a time (HapticTrapezoid::prefetch_change). Against the same
/// loop with no blade, run before it: tick median, p99, max, late ticks per 10,000.
std::string measure_blade(const std::filesystem::path& mesh_file, long roi_nodes, double speed, long ticks) {
  const auto brain = build_brain(mesh_file);
  const Condensed condensed = condense(*brain, roi_nodes);
  const model::SecondOrderSystem& system = condensed.condensation->system();
  const roi::Partition& partition = condensed.condensation->partition();
  const model::AverageAcceleration rule(1e-3);
  const double dt = rule.dt();
  const Index n = system.size();
  const std::vector<Index> position = roi_positions(*brain, partition);
  const std::vector<int> tool = tool_nodes(*brain, partition, 10);
  const std::vector<std::array<Index, 3>> held = held_dofs(*brain, position, tool);
  const std::vector<Index> allowed_list = roi_tetrahedra(*brain, partition, tool);
  std::vector<bool> allowed(static_cast<std::size_t>(brain->mesh.num_tets()), false);
  for (const Index e : allowed_list) allowed[static_cast<std::size_t>(e)] = true;
  cutting::Blade blade;
  blade.name = "benchmark";
  blade.edge_a = Vec3(0.006, -0.004, 0.048);
  blade.edge_b = Vec3(0.006, 0.004, 0.048);
  blade.start = 0.2;
  blade.path.displacement = Vec3(0, 0, -0.016);
  blade.path.ramp.duration = 0.016 / speed;
  std::vector<cutting::Crossing> schedule;
  long skipped = 0;
  for (const auto& c : cutting::swept_elements(blade, brain->mesh))
    if (c.time < static_cast<double>(ticks) * dt) {
      if (allowed[static_cast<std::size_t>(c.element)])
        schedule.push_back(c);
      else
        ++skipped;
    }
  const auto hand = [](long tick) { return Vec3(0.001 * std::min(static_cast<double>(tick) / 50.0, 1.0), 0, 0); };
  // Each loop paced as a device's is: tick k starts at (k - 1) dt after the first (spinning until
  // then; at once when behind), so that the blade and the background thread see the run's real time.
  const auto pace = [dt](const Stopwatch& run, long k) {
    while (run.seconds() < static_cast<double>(k - 1) * dt) {
    }
  };

  // The loop with no blade: alone, then beside a factorization of the same K_eff made again and
  // again in a second thread, as the background refactorization's worker makes them (SCHED_IDLE, the
  // BLAS on one thread), without its cuts: what sharing the machine alone costs a tick.
  const auto plain_loop = [&] {
    std::vector<double> seconds;
    model::SecondOrderSystem plain_system = system;
    integrators::HapticTrapezoid plain(plain_system, dt);
    plain.attach(held);
    model::State state = model::State::at_rest(n);
    plain.reset(state);
    const Stopwatch run;
    for (long k = 1; k <= ticks; ++k) {
      pace(run, k);
      const Stopwatch clock;
      plain.tick(hand(k), state);
      seconds.push_back(clock.seconds());
    }
    return seconds;
  };
  const std::vector<double> plain_s = plain_loop();
  std::vector<double> beside_s;
  {
    const SparseMatrix K_eff = rule.effective_stiffness(system);
    const std::vector<Index> last = system.dense_block_dofs();
    const solvers::BlasThreadsScope one_blas_thread(1);
    std::atomic<bool> stop{false};
    std::thread factoring([&] {
      const sched_param lowest{};
      pthread_setschedparam(pthread_self(), SCHED_IDLE, &lowest);
      while (!stop) {
        solvers::Cholesky again;
        again.compute(K_eff, last);
      }
    });
    beside_s = plain_loop();
    stop = true;
    factoring.join();
  }
  // The loop with the blade: its factor corrected alone (the columns ahead solved on this thread in
  // each tick's spare time), or also made afresh in the background (the columns ahead with each new
  // factor, the coming tetrahedra's dofs given at every cut).
  const auto unknowns_of = [&](Index e) {
    std::vector<Index> out;
    for (const int node : brain->mesh.tets[static_cast<std::size_t>(e)])
      for (int c = 0; c < 3; ++c)
        if (const int d = brain->model.dofs->free_dof(node, c); d >= 0) out.push_back(position[static_cast<std::size_t>(d)]);
    return out;
  };
  struct BladeRun {
    std::vector<double> seconds;
    long events = 0, removed = 0, swaps = 0, cold = 0;  // cold: cuts that solved columns when they came
    double event_max = 0, prefetched = 0, swap_max = 0;
  };
  const auto cut_loop = [&](bool background) {
    BladeRun run;
    model::SecondOrderSystem cut_system = system;
    integrators::HapticTrapezoid loop(cut_system, dt);
    loop.attach(held);
    if (background) loop.refactor_in_background();
    model::State state = model::State::at_rest(n);
    loop.reset(state);
    fem::ElementRemover remover(brain->mesh, *brain->model.dofs, brain->model.materials);
    std::size_t next = 0, ahead = 0;
    std::vector<Index> queue;                       // dofs of coming tetrahedra, to be solved ahead
    double column_s = simulation::median(plain_s);  // a column's solve costs about a tick's
    const auto expect_coming = [&](double t) {
      std::vector<Index> coming;
      for (std::size_t i = next; i < schedule.size() && schedule[i].time <= t + 0.5; ++i)
        for (const Index d : unknowns_of(schedule[i].element)) coming.push_back(d);
      loop.expect_change(std::move(coming));
    };
    if (background) expect_coming(0);
    const Stopwatch run_clock;
    for (long k = 1; k <= ticks; ++k) {
      pace(run_clock, k);
      const double t = static_cast<double>(k - 1) * dt;  // the state's time: the step's start
      const Stopwatch clock;
      std::vector<Index> due;
      for (; next < schedule.size() && schedule[next].time <= t; ++next) due.push_back(schedule[next].element);
      if (!due.empty()) {
        std::sort(due.begin(), due.end());
        const fem::ElementRemoval removal = remover.remove(due, 0.0);
        cut_haptic(loop, cut_system, state, removal, *brain->model.dofs, position);
        run.event_max = std::max(run.event_max, loop.change_seconds());
        run.cold += loop.change_solves() > 0 ? 1 : 0;
        ++run.events;
        run.removed += static_cast<long>(due.size());
      }
      if (background) {  // the coming tetrahedra, given again at every cut and as each enters the horizon
        bool coming = !due.empty();
        for (; ahead < schedule.size() && schedule[ahead].time <= t + 0.5; ++ahead) coming = true;
        if (coming) expect_coming(t);
      }
      const long swaps_before = loop.background_factors();
      loop.tick(hand(k), state);
      if (loop.background_factors() > swaps_before) run.swap_max = std::max(run.swap_max, loop.swap_seconds());
      if (!background) {
        for (; ahead < schedule.size() && schedule[ahead].time <= t + 0.5; ++ahead)
          for (const Index d : unknowns_of(schedule[ahead].element)) queue.push_back(d);
        // A column only where it ends before the deadline (its cost: the slowest one so far, at least a solve's).
        while (!queue.empty() && clock.seconds() + column_s < 0.9 * dt) {
          const Stopwatch column_clock;
          loop.prefetch_change({queue.back()});
          queue.pop_back();
          ++run.prefetched;
          column_s = std::max(column_s, column_clock.seconds());
        }
      }
      run.seconds.push_back(clock.seconds());
    }
    run.swaps = loop.background_factors();
    return run;
  };
  const BladeRun corrected = cut_loop(false), refreshed = cut_loop(true);
  solvers::Cholesky factor;  // its size: what a tick streams twice (L3 or memory)
  factor.compute(rule.effective_stiffness(system), system.dense_block_dofs());
  const double factor_mb = factor.factor_nonzeros() * 8e-6;
  const LoopTicks plain = loop_ticks(plain_s, dt), beside = loop_ticks(beside_s, dt), cut = loop_ticks(corrected.seconds, dt),
                  background = loop_ticks(refreshed.seconds, dt);
  const auto nodes = static_cast<long long>(brain->mesh.num_nodes());
  return format(
             "%8lld %5ld %5.1f %6ld %6zu %5ld %5ld | %7.3f %7.3f %7.2f %6.1f | %7.3f %7.3f %6.1f | %7.3f %7.3f %7.2f %6.1f "
             "%8.2f %4ld | %7.3f %7.3f %7.2f %6.1f %8.2f %4ld %5ld %7.3f %6.1f\t",
             nodes, roi_nodes, speed * 1e3, ticks, schedule.size(), skipped, corrected.events, plain.median * 1e3,
             plain.p99 * 1e3, plain.max * 1e3, plain.late_per_10k, beside.median * 1e3, beside.p99 * 1e3, beside.late_per_10k,
             cut.median * 1e3, cut.p99 * 1e3, cut.max * 1e3, cut.late_per_10k, corrected.event_max * 1e3, corrected.cold,
             background.median * 1e3, background.p99 * 1e3, background.max * 1e3, background.late_per_10k,
             refreshed.event_max * 1e3, refreshed.cold, refreshed.swaps, refreshed.swap_max * 1e3, factor_mb) +
         format("%lld,%ld,%g,%ld,%zu,%ld,%ld,%ld,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%ld,%.0f,", nodes, roi_nodes,
                speed * 1e3, ticks, schedule.size(), skipped, corrected.events, corrected.removed, plain.median * 1e3,
                plain.p99 * 1e3, plain.max * 1e3, plain.late_per_10k, cut.median * 1e3, cut.p99 * 1e3, cut.max * 1e3,
                cut.late_per_10k, corrected.event_max * 1e3, corrected.cold, corrected.prefetched) +
         format("%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%ld,%ld,%.6g,%.4g\n", beside.median * 1e3, beside.p99 * 1e3,
                beside.late_per_10k, background.median * 1e3, background.p99 * 1e3, background.max * 1e3, background.late_per_10k,
                refreshed.event_max * 1e3, refreshed.cold, refreshed.swaps, refreshed.swap_max * 1e3, factor_mb);
}

/// Split mode on the same brain and ROI, run as a scenario (the copies are the model's from the
/// start): a blade beside the opening whose edge and depth are `size` mm, through in one step at
/// t = 4.5 ms. The step that takes the split (separating the faces, splitting the nodes, Woodbury's
/// correction of the factor, the step) against the steps before and after, and a numeric
/// refactorization of the split K_eff (pattern analysed beforehand). One line per size.
std::string measure_split(const std::filesystem::path& mesh_file, long roi_nodes, const std::vector<double>& sizes) {
  std::string lines;
  for (const double size : sizes) {
    const double x = 6, top = 40 + size / 2;
    const std::string text = format(
        "mesh = \"%s\"\n[material]\npreset = \"paper\"\n[boundary]\nfixed = [\"base\"]\n"
        "[[load]]\nset = \"opening_left\"\nforce_N = [-0.01601, 0.0, 0.0]\nramp_s = 0.5\n"
        "[[load]]\nset = \"opening_right\"\nforce_N = [0.01601, 0.0, 0.0]\nramp_s = 0.5\n"
        "[roi]\nkind = \"nearest\"\ntarget_mm = [0.0, 0.0, 40.0]\nnodes = %ld\n"
        "[[cut]]\nmode = \"split\"\nedge_from_mm = [%g, %g, %g]\nedge_to_mm = [%g, %g, %g]\nmove_mm = [0.0, 0.0, %g]\n"
        "start_s = 0.0045\nduration_s = 0.000001\n[time]\nintegrator = \"trapezoid\"\ndt_s = 0.001\nsteps = 12\n",
        std::filesystem::absolute(mesh_file).c_str(), roi_nodes, x, -size / 2, top, x, size / 2, top, -size);
    const scenario::Scenario sc = scenario::parse_scenario(text, "split-benchmark.toml", mesh_file.parent_path());
    std::unique_ptr<simulation::ScenarioStepper> stepper;
    try {
      stepper = std::make_unique<simulation::ScenarioStepper>(sc, false);
    } catch (const InputError& e) {
      lines += format("%8s %5ld %5g  refused: %s\t\n", "-", roi_nodes, size, e.what());
      continue;
    }
    std::size_t faces = 0, splits = 0, changed = 0;
    stepper->on_cut([&](const simulation::CutEvent& e, const model::State&) {
      faces += e.faces_separated;
      splits += e.splits.size();
      changed += e.change.dofs.size();
    });
    std::vector<double> before, after;
    double event_s = 0;
    for (int k = 0; k < 12; ++k) {
      const Stopwatch clock;
      stepper->step();
      (k < 5 ? before : after).push_back(clock.seconds());
      if (k == 5) event_s = clock.seconds(), after.pop_back();
    }
    const model::SecondOrderSystem& system = stepper->model().system();
    const model::AverageAcceleration rule(sc.dt);
    const SparseMatrix K_eff = rule.effective_stiffness(system);
    solvers::Cholesky refactored;
    refactored.analyze(K_eff, system.dense_block_dofs());
    const double refactor_s = median_seconds(3, [&] { refactored.factorize(K_eff); });
    const auto nodes = static_cast<long long>(stepper->model().split_plan->num_nodes);
    lines += format("%8lld %5ld %5g %6zu %6zu %5zu %9.3f %9.3f %8.3f %10.1f\t", nodes, roi_nodes, size, faces, splits, changed,
                    simulation::median(before) * 1e3, event_s * 1e3, simulation::median(after) * 1e3, refactor_s * 1e3) +
             format("%lld,%ld,%g,%zu,%zu,%zu,%.6g,%.6g,%.6g,%.6g\n", nodes, roi_nodes, size, faces, splits, changed,
                    simulation::median(before) * 1e3, event_s * 1e3, simulation::median(after) * 1e3, refactor_s * 1e3);
  }
  return lines;
}

/// Runs `work` in a child per brain and ROI, printing its table lines and writing its CSV rows.
void each_model(const Options& o, io::CsvWriter& csv,
                const std::function<std::string(const std::filesystem::path&, long)>& work) {
  for (const long n : o.nodes) {
    const auto mesh_file = brain_mesh_file(n);
    for (const long roi : o.rois) {
      const ChildResult child = run_in_child([&] { return work(mesh_file, roi); }, o.model_timeout_s);
      if (!child.ok) {
        std::printf("%8ld %5ld  failed: %s\n", n, roi, child.output.c_str());
        continue;
      }
      std::size_t at = 0;
      while (at < child.output.size()) {
        const std::size_t bar = child.output.find('\t', at), end = child.output.find('\n', bar);
        std::printf("%s\n", child.output.substr(at, bar - at).c_str());
        if (end > bar + 1) csv.row(child.output.substr(bar + 1, end - bar - 1));
        at = end + 1;
      }
      std::fflush(stdout);
    }
  }
}

int run(const Options& o) {
  std::filesystem::create_directories(o.out);
  if (o.machine_bounds) report_machine_bounds(o.out);
  io::CsvWriter csv(
      o.out / "cut.csv",
      "nodes,roi_nodes,system_dofs,interface_dofs,removed,changed_dofs,form_ms,update_ms,solve_ms,"
      "solve_after_ms,refactor_ms,condense_s,gap_vs_refactored,haptic_event_ms,tick_before_ms,tick_after_ms,ahead_ms,"
      "ahead_event_ms");
  std::printf(
      "Cut: tetrahedra nearest the target (clear of the tool) removed from the condensed ROI's K_eff (trapezoid, dt = 1 ms); "
      "the change taken by Woodbury's correction of the factor, against a numeric refactorization and the whole "
      "condensation; then in the haptic loop (a tool on 10 wall nodes): the event, the ticks it spans, the tick before and "
      "after; and with the cut's columns solved ahead (between earlier ticks): their cost, the event, its ticks\n");
  std::printf("%8s %5s %6s %6s %5s %5s %8s %9s %8s %8s %10s %9s  %7s | %8s %5s %7s %7s | %8s %8s %5s\n", "nodes", "ROI", "dofs",
              "iface", "cut", "r", "form ms", "update ms", "solve ms", "after ms", "refactor ms", "condense s", "gap", "event ms",
              "ticks", "tick ms", "after ms", "ahead ms", "event ms", "ticks");
  if (o.cut_table)
    each_model(o, csv, [&](const std::filesystem::path& mesh_file, long roi) { return measure(mesh_file, roi, o.cuts); });
  if (o.blade_ticks > 0) {
    io::CsvWriter blade_csv(o.out / "blade.csv",
                            "nodes,roi_nodes,speed_mm_s,ticks,tetrahedra,skipped,events,removed,plain_median_ms,plain_p99_ms,"
                            "plain_max_ms,plain_late_per_10k,cut_median_ms,cut_p99_ms,cut_max_ms,cut_late_per_10k,event_max_ms,"
                            "cold_cuts,columns_ahead,beside_median_ms,beside_p99_ms,beside_late_per_10k,background_median_ms,"
                            "background_p99_ms,background_max_ms,"
                            "background_late_per_10k,background_event_max_ms,background_cold_cuts,background_factors,swap_max_ms,"
                            "factor_mb");
    std::printf(
        "\nBlade in the loop: an 8 mm edge beside the opening swept 16 mm down at %g mm/s from t = 0.2 s while the haptic loop "
        "runs (1 kHz, paced; a tool on 10 wall nodes); each tetrahedron removed at the tick the blade reaches it. Ticks (ms) "
        "without the blade, alone and beside a factorization of the same K_eff repeated in a second thread; then with the blade "
        "(late: over 1 ms, per 10,000), the largest cut event (ms) and the cuts that solved "
        "columns when they came (cold): the factor corrected alone (the next tetrahedra's columns solved ahead in each tick's "
        "spare time), then also made afresh in a second thread (each new factor with the columns of the tetrahedra due within "
        "0.5 s; the factors swapped in, the largest swap, ms); the factor's size (MB of L's values, which a tick reads twice)\n",
        o.blade_speed * 1e3);
    std::printf(
        "%8s %5s %5s %6s %6s %5s %5s | %7s %7s %7s %6s | %7s %7s %6s | %7s %7s %7s %6s %8s %4s | %7s %7s %7s %6s %8s %4s %5s %7s "
        "%6s\n",
        "nodes", "ROI", "mm/s", "ticks", "tets", "skip", "cuts", "median", "p99", "max", "late", "median", "p99", "late",
        "median", "p99", "max", "late", "event ms", "cold", "median", "p99", "max", "late", "event ms", "cold", "swaps",
        "swap ms", "L MB");
    each_model(o, blade_csv, [&](const std::filesystem::path& mesh_file, long roi) {
      return measure_blade(mesh_file, roi, o.blade_speed, o.blade_ticks);
    });
    blade_csv.close();
    std::printf("wrote %s\n", (o.out / "blade.csv").c_str());
  }
  if (!o.split_sizes.empty()) {
    io::CsvWriter split_csv(
        o.out / "split.csv",
        "nodes,roi_nodes,blade_mm,faces,splits,changed_dofs,step_before_ms,split_step_ms,step_after_ms,refactor_ms");
    std::printf(
        "\nSplit: a blade beside the opening (edge and depth `blade` mm) through in one step, as a scenario (trapezoid, dt = "
        "1 ms): the faces it separates, the node splits, the changed dofs r; a step before, the step taking the split "
        "(Woodbury's correction), a step after, against a numeric refactorization of the split K_eff\n");
    std::printf("%8s %5s %5s %6s %6s %5s %9s %9s %8s %10s\n", "nodes", "ROI", "blade", "faces", "splits", "r", "before ms",
                "split ms", "after ms", "refactor ms");
    each_model(o, split_csv,
               [&](const std::filesystem::path& mesh_file, long roi) { return measure_split(mesh_file, roi, o.split_sizes); });
    split_csv.close();
    std::printf("wrote %s\n", (o.out / "split.csv").c_str());
  }
  csv.close();
  std::printf("wrote %s\n", (o.out / "cut.csv").c_str());
  return 0;
}

}  // namespace
}  // namespace roifem::bench

int main(int argc, char** argv) {
  roifem::bench::Options o;
  CLI::App app(
      "roifem cut benchmark: a cut of 1, 10 and 100 tetrahedra inside the ROI of condensed brains, taken into the\n"
      "trapezoidal rule's factor by Woodbury's correction, against refactorizing and re-condensing");
  app.add_option("--nodes", o.nodes, "brain sizes (nodes; meshes cached in $ROIFEM_MESH_CACHE)");
  app.add_option("--rois", o.rois, "ROI sizes (nodes nearest the target)");
  app.add_option("--cuts", o.cuts, "tetrahedra removed per cut");
  app.add_option("--blade-ticks", o.blade_ticks, "the blade-in-the-loop run's ticks (0: skip)");
  app.add_option("--blade-speed-mm-s", o.blade_speed, "the blade's speed (mm/s)")->transform([](const std::string& v) {
    return std::to_string(std::stod(v) * 1e-3);
  });
  app.add_option("--split-sizes", o.split_sizes, "split mode: blade edge and depth (mm), one scenario each (none: skip)");
  app.add_option("--out", o.out, "output directory (cut.csv)");
  app.add_flag("!--no-cut-table", o.cut_table, "skip the cut events' table (the blade and split runs alone)");
  app.add_flag("!--no-machine-bounds", o.machine_bounds, "skip measuring the machine's bounds (smoke tests)");
  CLI11_PARSE(app, argc, argv);
  return roifem::bench::run(o);
}
