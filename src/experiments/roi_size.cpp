// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/roi_size.hpp"
#include "common/format.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <ostream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "condensation/reduced_model.hpp"
#include "experiments/roi_error.hpp"
#include "integrators/factory.hpp"
#include "io/result_table.hpp"
#include "model/hyperelastic_force.hpp"
#include "simulation/progress.hpp"
#include "simulation/run_loop.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::experiments {

namespace {

/// The full model's run, and the peak error of reduced models against it at the evaluated nodes.
class ErrorProbe {
 public:
  ErrorProbe(const scenario::Scenario& sc, std::string integrator, simulation::ScenarioModel& full)
      : sc_(sc),
        integrator_(std::move(integrator)),
        full_(full),
        evaluated_(full_node_dofs(roi::select_roi_nodes(full.mesh, *full.full.dofs, *sc.roi), *full.full.dofs)) {
    auto integrator_run = integrators::make_integrator(integrator_, sc.dt);
    model::State state = model::State::at_rest(full.system().size());
    integrator_run->reset(full.system(), state);
    for (long k = 1; k <= sc.steps; ++k) {
      integrator_run->advance_to(static_cast<double>(k) * sc.dt, state);
      reference_.push_back(state.u);
    }
  }

  /// Peak over steps and the evaluated nodes of the distance to the full model (mm).
  double peak_error_mm(condensation::ReducedModel& reduced) const { return peak_distance_mm(run(reduced), reference_); }

  /// A neo-Hookean model's hybrid ROI, its error split: the full model with the hybrid's law but
  /// uncondensed (the linear remainder's error alone, against the full neo-Hookean model), and the
  /// hybrid against that model (the condensation's error alone).
  RoiSizeProbe probe_hybrid(Index nodes, condensation::ReducedModel& hybrid) const {
    const std::vector<Vector> h = run(hybrid);
    model::SecondOrderSystem uncondensed = full_.system();
    const model::FemModel& f = full_.full;
    uncondensed.internal_force =
        model::hybrid_law_uncondensed(*f.mesh, *f.dofs, f.materials, f.element, hybrid.partition(), f.system.K, f.tools.tools());
    const std::vector<Vector> m = run(uncondensed);
    return {.nodes = nodes,
            .peak_max_mm = peak_distance_mm(h, reference_),
            .remainder_mm = peak_distance_mm(m, reference_),
            .condensation_mm = peak_distance_mm(h, m)};
  }

  /// The reduced model of the ROI `spec` (a POD basis learns from the scenario's own step and length).
  std::unique_ptr<condensation::ReducedModel> reduce(const roi::RoiSpec& spec, const condensation::Reduction& reduction) const {
    const fem::DofMap& dofs = *full_.full.dofs;
    const auto partition = roi::partition_dofs(full_.system().K, dofs, roi::select_roi_nodes(full_.mesh, dofs, spec));
    return simulation::reduce_full_model(full_.full, partition, reduction.trained_on(sc_.dt, sc_.steps), sc_.file.string());
  }
  std::unique_ptr<condensation::ReducedModel> reduce(Index nodes, const condensation::Reduction& reduction) const {
    return reduce({.kind = roi::RoiSpec::Kind::nearest, .center = sc_.roi->center, .radius = 0, .count = nodes, .set = {}},
                  reduction);
  }

  double step_median(const model::SecondOrderSystem& system, long steps) const {
    auto integrator = integrators::make_integrator(integrator_, sc_.dt);
    model::State state = model::State::at_rest(system.size());
    integrator->reset(system, state);
    std::vector<double> seconds;
    for (long k = 1; k <= steps; ++k) {
      const Stopwatch clock;
      integrator->advance_to(static_cast<double>(k) * sc_.dt, state);
      seconds.push_back(clock.seconds());
    }
    return simulation::median(seconds);
  }

 private:
  /// The reduced model's run, over every free dof (u_s recovered) at steps 1..steps.
  std::vector<Vector> run(condensation::ReducedModel& reduced) const {
    std::vector<Vector> u;
    run(reduced.system(), [&](const model::State& s) { u.push_back(reduced.expand(s.u, s.t)); });
    return u;
  }
  /// A full model's run.
  std::vector<Vector> run(const model::SecondOrderSystem& full) const {
    std::vector<Vector> u;
    run(full, [&](const model::State& s) { u.push_back(s.u); });
    return u;
  }
  template <class Record>
  void run(const model::SecondOrderSystem& system, Record&& record) const {
    auto integrator = integrators::make_integrator(integrator_, sc_.dt);
    model::State state = model::State::at_rest(system.size());
    integrator->reset(system, state);
    for (long k = 1; k <= sc_.steps; ++k) {
      integrator->advance_to(static_cast<double>(k) * sc_.dt, state);
      record(state);
    }
  }
  /// Peak over the steps of the largest distance at the evaluated nodes (mm).
  double peak_distance_mm(const std::vector<Vector>& a, const std::vector<Vector>& b) const {
    double peak = 0;
    for (std::size_t k = 0; k < a.size(); ++k) peak = std::max(peak, roi_error(evaluated_, a[k], b[k]).max);
    return peak / mm;
  }

  const scenario::Scenario& sc_;
  std::string integrator_;
  simulation::ScenarioModel& full_;
  RoiNodeDofs evaluated_;  // the nodes where the error is measured
  std::vector<Vector> reference_;
};

using io::Cell;
using io::Column;

const std::array<Column<RoiSizeRow>, 11> roi_size_table{{
    {"reduction", "the static part's reduction", [](const RoiSizeRow& r) -> Cell { return r.reduction; }},
    {"found", "1: a size from which every larger ROI tried holds", [](const RoiSizeRow& r) -> Cell { return r.found; }},
    {"nodes", "that size: the ROI's nodes", [](const RoiSizeRow& r) -> Cell { return static_cast<long>(r.nodes); }},
    {"dofs", "the reduced system's degrees of freedom there",
     [](const RoiSizeRow& r) -> Cell { return static_cast<long>(r.dofs); }},
    {"peak_max_mm", "its peak max error over the run (mm)", [](const RoiSizeRow& r) -> Cell { return r.peak_max_mm; }, "%.9g"},
    {"step_s_median", "its median step cost (s)", [](const RoiSizeRow& r) -> Cell { return r.step_s_median; }, "%.6e"},
    {"evaluations", "the sizes tried", [](const RoiSizeRow& r) -> Cell { return static_cast<long>(r.probes.size()); }},
    {"max_error_mm", "the budget (mm)", [](const RoiSizeRow& r) -> Cell { return r.max_error_mm; }, "%g"},
    {"misses_from", "the smallest size tried that misses the budget (0: none)",
     [](const RoiSizeRow& r) -> Cell { return static_cast<long>(r.missing_from); }},
    {"misses_to", "the largest size tried that misses it (0: none)",
     [](const RoiSizeRow& r) -> Cell { return static_cast<long>(r.missing_to); }},
    {"holds_below", "the largest size below the misses that holds (0: none; else the error is not monotone in the size)",
     [](const RoiSizeRow& r) -> Cell { return static_cast<long>(r.holds_below); }},
}};

Cell optional_figure(const std::optional<double>& x) { return x ? Cell(*x) : Cell(); }

const std::array<Column<RoiSizeRun>, 6> roi_size_run_table{{
    {"reduction", "the static part's reduction", [](const RoiSizeRun& r) -> Cell { return r.row->reduction; }},
    {"nodes", "the ROI's nodes", [](const RoiSizeRun& r) -> Cell { return static_cast<long>(r.probe.nodes); }},
    {"peak_max_mm", "the peak max error over the run (mm)", [](const RoiSizeRun& r) -> Cell { return r.probe.peak_max_mm; },
     "%.9g"},
    {"within_budget", "1: peak_max_mm <= the budget",
     [](const RoiSizeRun& r) -> Cell { return r.probe.holds(r.row->max_error_mm); }},
    {"remainder_mm",
     "neo-hookean: the peak error of the full model with the hybrid's law, uncondensed, against the full neo-Hookean "
     "model: the linear remainder's error (mm)",
     [](const RoiSizeRun& r) { return optional_figure(r.probe.remainder_mm); }, "%.9g"},
    {"condensation_mm", "neo-hookean: the peak error of the hybrid against that uncondensed model: the condensation's (mm)",
     [](const RoiSizeRun& r) { return optional_figure(r.probe.condensation_mm); }, "%.9g"},
}};

/// The two result tables, rewritten (atomically) after every run, so that a search stopped early
/// keeps what it found.
void write_files(const std::filesystem::path& out, const RoiSizeResults& results, const RoiSizeRow* current) {
  if (out.empty()) return;
  std::vector<RoiSizeRun> runs;
  for (const auto& row : results.rows) std::ranges::copy(runs_of(row), std::back_inserter(runs));
  if (current) std::ranges::copy(runs_of(*current), std::back_inserter(runs));
  io::write_csv(out / "roi_size_runs.csv", roi_size_run_columns(), runs);
  io::write_csv(out / "roi_size.csv", roi_size_columns(), results.rows);
}

/// The answer from the probes: the smallest size tried above every miss, and the stretch below.
void conclude(RoiSizeRow& row, double budget) {
  std::vector<RoiSizeProbe> sorted = row.probes;
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.nodes < b.nodes; });
  const auto last_miss = std::find_if(sorted.rbegin(), sorted.rend(), [&](const auto& p) { return !p.holds(budget); });
  const auto answer = last_miss.base();  // first size after the largest miss
  row.found = answer != sorted.end();
  if (row.found) {
    row.nodes = answer->nodes;
    row.peak_max_mm = answer->peak_max_mm;
  }
  // Neo-Hookean: from which size on the linear remainder errs no more than the condensation (both
  // at rounding level, 1e-9 of the budget, count as equal: every node in the ROI leaves neither).
  const auto remainder_over = std::find_if(sorted.rbegin(), sorted.rend(), [&](const auto& p) {
    return p.remainder_mm && *p.remainder_mm > *p.condensation_mm + 1e-9 * budget;
  });
  if (remainder_over.base() != sorted.end() && sorted.front().remainder_mm)
    row.remainder_below_condensation_from = remainder_over.base()->nodes;
  if (last_miss == sorted.rend()) return;
  row.missing_to = last_miss->nodes;
  const auto first_miss = std::find_if(sorted.begin(), sorted.end(), [&](const auto& p) { return !p.holds(budget); });
  row.missing_from = first_miss->nodes;
  if (first_miss != sorted.begin()) row.holds_below = std::prev(first_miss)->nodes;
}

class Search {
 public:
  Search(const RoiSizeOptions& o, const ErrorProbe& probe, Index free_nodes, RoiSizeResults& results)
      : o_(o),
        probe_(probe),
        coarse_(geometric_sizes(std::min(o.start_nodes, free_nodes), free_nodes, o.coarse)),
        progress_("roi-size", static_cast<long>(o.reductions.size() * (coarse_.size() + fine_estimate())), 0.5, "runs"),
        results_(results) {}

  RoiSizeRow find(const condensation::Reduction& reduction) {
    RoiSizeRow row{.reduction = reduction.label(), .max_error_mm = o_.max_error_mm};
    auto holds = [&](Index n) {
      const auto reduced = probe_.reduce(n, reduction);
      row.probes.push_back(reduced->system().is_nonlinear()
                               ? probe_.probe_hybrid(n, *reduced)
                               : RoiSizeProbe{.nodes = n, .peak_max_mm = probe_.peak_error_mm(*reduced)});
      write_files(o_.out, results_, &row);
      progress_.update(++runs_, format("%s: %lld nodes %.4f mm", row.reduction.c_str(), static_cast<long long>(n),
                                       row.probes.back().peak_max_mm));
      return row.probes.back().holds(o_.max_error_mm);
    };
    // The whole coarse grid, largest first (the end that must hold: an ROI of every node is the full model).
    Index largest_miss = 0;
    for (auto n = coarse_.rbegin(); n != coarse_.rend(); ++n)
      if (!holds(*n)) largest_miss = std::max(largest_miss, *n);
    // Between the largest miss and the next coarse size, the fine grid downwards to the first miss.
    if (largest_miss > 0 && largest_miss < coarse_.back()) {
      const Index next = *std::upper_bound(coarse_.begin(), coarse_.end(), largest_miss);
      const auto fine = geometric_sizes(largest_miss, next, o_.resolution);
      for (auto n = fine.rbegin(); n != fine.rend(); ++n)
        if (*n != next && *n != largest_miss && !holds(*n)) break;
    }
    conclude(row, o_.max_error_mm);
    if (row.found) {
      const auto reduced = probe_.reduce(row.nodes, reduction);
      row.dofs = reduced->system().size();
      row.step_s_median = probe_.step_median(reduced->system(), o_.timing_steps);
    }
    return row;
  }

 private:
  std::size_t fine_estimate() const {
    return static_cast<std::size_t>(std::ceil(std::log1p(o_.coarse) / std::log1p(o_.resolution)));
  }
  const RoiSizeOptions& o_;
  const ErrorProbe& probe_;
  std::vector<Index> coarse_;
  simulation::ProgressReporter progress_;
  long runs_ = 0;
  RoiSizeResults& results_;
};

std::string row_text(const RoiSizeRow& r) {
  if (!r.found) return format("  %-18s misses the budget even with every node in the ROI\n", r.reduction.c_str());
  std::string text = format("  %-18s from %lld node%s on, every ROI tried holds (%.4f mm there)", r.reduction.c_str(),
                            static_cast<long long>(r.nodes), r.nodes == 1 ? "" : "s", r.peak_max_mm);
  if (r.missing_to > 0)
    text += format("; misses at %lld-%lld nodes", static_cast<long long>(r.missing_from), static_cast<long long>(r.missing_to));
  if (r.holds_below > 0)
    text += format("; holds again at %lld nodes and below (the error is not monotone in the ROI size)",
                   static_cast<long long>(r.holds_below));
  if (!r.probes.empty() && r.probes.front().remainder_mm) {
    if (r.remainder_below_condensation_from > 0) {
      const auto& at = *std::find_if(r.probes.begin(), r.probes.end(),
                                     [&](const RoiSizeProbe& p) { return p.nodes == r.remainder_below_condensation_from; });
      text += format(
          "\n  %-18s the linear remainder's error stays at or below the condensation's from %lld nodes on (%.4f mm against "
          "%.4f mm there)",
          "", static_cast<long long>(r.remainder_below_condensation_from), *at.remainder_mm, *at.condensation_mm);
    } else {
      text += format("\n  %-18s the linear remainder's error stays above the condensation's at every size tried", "");
    }
  }
  return text + "\n";
}

void print_summary(const RoiSizeResults& results, double budget, std::ostream& log) {
  log << format("\nROI size for max error <= %g mm: the size from which every larger ROI tried holds\n", budget);
  log << format("(full model: %lld free nodes, %.4f ms per step)\n", static_cast<long long>(results.free_nodes),
                results.full_step_s_median * 1e3);
  log << format("  %-18s %7s %6s %15s %11s %9s %6s  %s\n", "reduction", "nodes", "dofs", "peak max (mm)", "step (ms)", "vs full",
                "runs", "misses at (nodes)");
  for (const auto& r : results.rows) {
    if (!r.found) {
      log << format("  %-18s   none within the mesh\n", r.reduction.c_str());
      continue;
    }
    const std::string misses =
        r.missing_to > 0 ? format("%lld-%lld", static_cast<long long>(r.missing_from), static_cast<long long>(r.missing_to))
                         : "none";
    log << format("  %-18s %7lld %6lld %15.4f %11.4f %8.2fx %6zu  %s\n", r.reduction.c_str(), static_cast<long long>(r.nodes),
                  static_cast<long long>(r.dofs), r.peak_max_mm, r.step_s_median * 1e3,
                  r.step_s_median / results.full_step_s_median, r.probes.size(), misses.c_str());
  }
}

}  // namespace

std::vector<Index> geometric_sizes(Index start, Index last, double ratio) {
  std::vector<Index> sizes;
  for (Index n = std::max<Index>(1, start); n < last;
       n = std::max<Index>(n + 1, static_cast<Index>(std::ceil((1 + ratio) * static_cast<double>(n)))))
    sizes.push_back(n);
  sizes.push_back(last);
  return sizes;
}

RoiSizeResults run_roi_size(const RoiSizeOptions& o, std::ostream& log) {
  if (!(o.max_error_mm > 0) || !std::isfinite(o.max_error_mm))
    throw InputError("roi-size: --max-error-mm must be positive (got " + number_text(o.max_error_mm) + ")");
  if (o.reductions.empty()) throw InputError("roi-size: no reduction to size");
  if (!(o.coarse > 0) || !(o.resolution > 0) || o.resolution > o.coarse)
    throw InputError("roi-size: --coarse and --resolution must be positive, the resolution the finer (got " +
                     number_text(o.coarse) + " and " + number_text(o.resolution) + ")");
  integrators::integrator_info(o.integrator);  // an unknown name stops here, listing the valid ones
  const scenario::Scenario sc = scenario::read_scenario(o.scenario);
  scenario::refuse_run_only_tables(sc, "roifem roi-size");
  if (!sc.roi || (sc.roi->kind != roi::RoiSpec::Kind::ball && sc.roi->kind != roi::RoiSpec::Kind::nearest))
    throw InputError(sc.file.string() +
                     ": roi-size needs an ROI target: [roi] kind = \"nearest\" (target_mm) or \"ball\" (center_mm)");
  if (!o.out.empty()) check_output_directory(o.out);
  scenario::Scenario full_scenario = sc;
  full_scenario.roi.reset();
  const auto full = simulation::build_scenario_model(full_scenario);

  RoiSizeResults results;
  results.target = sc.roi->center;
  results.free_nodes = static_cast<Index>(roi::free_nodes(full->mesh, *full->full.dofs).size());
  log << format(
      "roi-size: %s, %lld free nodes; ROI = the N nodes nearest (%g, %g, %g) mm; budget: max error <= %g mm at the "
      "scenario's ROI (%s) over %ld steps of %s at dt = %g s (full model and ROI models alike)\n",
      sc.file.c_str(), static_cast<long long>(results.free_nodes), results.target.x() / mm, results.target.y() / mm,
      results.target.z() / mm, o.max_error_mm, sc.roi->describe().c_str(), sc.steps, o.integrator.c_str(), sc.dt);
  std::vector<condensation::Reduction> reductions = o.reductions;
  if (full->system().is_nonlinear()) {  // the hybrid ROI: static condensation under a nonlinear ROI
    std::string left_out;
    std::erase_if(reductions, [&](const condensation::Reduction& r) {
      if (r.is_static_condensation()) return false;
      left_out += (left_out.empty() ? "" : ", ") + r.label();
      return true;
    });
    if (!left_out.empty())
      log << "a neo-hookean model: " << left_out
          << " left out (a reduction by modes linearizes the ROI's motion); static condensation sizes the hybrid ROI\n";
    if (reductions.empty()) reductions.push_back(condensation::parse_reduction("static"));
  }
  const ErrorProbe probe(sc, o.integrator, *full);
  results.full_step_s_median = probe.step_median(full->system(), o.timing_steps);
  {  // the scenario's own ROI, as it stands
    const auto own = probe.reduce(*sc.roi, sc.reduction);
    results.scenario_roi = sc.roi->describe() + ", " + sc.reduction.label();
    results.scenario_roi_nodes = static_cast<Index>(own->partition().roi_nodes.size());
    results.scenario_peak_max_mm = probe.peak_error_mm(*own);
    log << format("the scenario's own ROI (%s: %lld nodes) peaks at %.4f mm: %s the %g mm budget\n", results.scenario_roi.c_str(),
                  static_cast<long long>(results.scenario_roi_nodes), results.scenario_peak_max_mm,
                  results.scenario_peak_max_mm <= o.max_error_mm ? "within" : "OVER", o.max_error_mm);
  }
  Search search(o, probe, results.free_nodes, results);
  for (const auto& reduction : reductions) {
    results.rows.push_back(search.find(reduction));
    write_files(o.out, results, nullptr);
    log << row_text(results.rows.back()) << std::flush;
  }
  print_summary(results, o.max_error_mm, log);
  if (!o.out.empty())
    log << "results: " << (o.out / "roi_size.csv").string() << ", " << (o.out / "roi_size_runs.csv").string() << '\n';
  return results;
}

std::vector<RoiSizeRun> runs_of(const RoiSizeRow& row) {
  std::vector<RoiSizeRun> runs;
  for (const auto& p : row.probes) runs.push_back({&row, p});
  return runs;
}

std::span<const io::Column<RoiSizeRow>> roi_size_columns() { return roi_size_table; }
std::span<const io::Column<RoiSizeRun>> roi_size_run_columns() { return roi_size_run_table; }

}  // namespace roifem::experiments
