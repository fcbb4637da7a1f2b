#include "experiments/roi_size.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "condensation/reduced_model.hpp"
#include "experiments/roi_error.hpp"
#include "integrators/factory.hpp"
#include "io/csv.hpp"
#include "simulation/run_loop.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::experiments {

namespace {

using io::format;

class Search {
 public:
  Search(const RoiSizeOptions& o, const scenario::Scenario& sc, const simulation::ScenarioModel& full, std::ostream& log)
      : o_(o),
        sc_(sc),
        full_(full),
        log_(log),
        evaluated_(full_node_dofs(roi::select_roi_nodes(full.mesh, *full.full.dofs, *sc.roi), *full.full.dofs)) {
    auto integrator = integrators::make_integrator(sc.integrator, sc.dt);
    model::State state = model::State::at_rest(full.system().size());
    integrator->reset(full.system(), state);
    for (long k = 1; k <= sc.steps; ++k) {
      integrator->advance_to(static_cast<double>(k) * sc.dt, state);
      reference_.push_back(state.u);
    }
  }

  /// Peak over steps and the evaluated nodes (the scenario's own ROI) of the distance to the full
  /// model (mm), for an ROI of the n nodes nearest the target (the static part recovered where the
  /// evaluated nodes lie outside it).
  double peak_error_mm(Index n, const condensation::Reduction& reduction) {
    const auto reduced = reduce(n, reduction);
    auto integrator = integrators::make_integrator(sc_.integrator, sc_.dt);
    const auto& system = reduced->system();
    model::State state = model::State::at_rest(system.size());
    integrator->reset(system, state);
    double peak = 0;
    for (long k = 1; k <= sc_.steps; ++k) {
      integrator->advance_to(static_cast<double>(k) * sc_.dt, state);
      peak = std::max(peak,
                      roi_error(evaluated_, reduced->expand(state.u, state.t), reference_[static_cast<std::size_t>(k - 1)]).max);
    }
    return peak / mm;
  }

  std::unique_ptr<condensation::ReducedModel> reduce(Index n, const condensation::Reduction& reduction) const {
    const roi::RoiSpec spec{.kind = roi::RoiSpec::Kind::nearest, .center = sc_.roi->center, .radius = 0, .count = n, .set = {}};
    const fem::DofMap& dofs = *full_.full.dofs;
    const auto partition = roi::partition_dofs(full_.system().K, dofs, roi::select_roi_nodes(full_.mesh, dofs, spec));
    // A POD basis learns from the scenario's own step and length.
    return std::make_unique<condensation::ReducedModel>(full_.system(), partition, dofs, reduction.trained_on(sc_.dt, sc_.steps));
  }

  RoiSizeRow find(const condensation::Reduction& reduction, Index free_nodes) {
    RoiSizeRow row{.reduction = reduction.label()};
    auto holds = [&](Index n) {
      const double peak = peak_error_mm(n, reduction);
      ++row.evaluations;
      log_ << format("  %-18s %6lld nodes: peak max error %.4f mm %s %g mm\n", row.reduction.c_str(), static_cast<long long>(n),
                     peak, peak <= o_.max_error_mm ? "<=" : "> ", o_.max_error_mm);
      if (peak <= o_.max_error_mm && (!row.found || n < row.nodes)) {
        row.found = true;
        row.nodes = n;
        row.peak_max_mm = peak;
      }
      return peak <= o_.max_error_mm;
    };
    // Ascending scan: the error is not monotone in N (the ROI boundary crossing the loaded walls or
    // a stiff region moves it up and down), so bisection could step over the smallest answer.
    for (Index n = std::min(o_.start_nodes, free_nodes);;
         n = std::min<Index>(free_nodes, std::max<Index>(n + 1, static_cast<Index>(std::ceil((1 + o_.resolution) * n))))) {
      if (holds(n)) break;
      if (n == free_nodes) return row;
    }
    // Step cost of the answer.
    const auto reduced = reduce(row.nodes, reduction);
    row.dofs = reduced->system().size();
    row.step_s_median = step_median(reduced->system());
    return row;
  }

  double step_median(const model::SecondOrderSystem& system) const {
    auto integrator = integrators::make_integrator(sc_.integrator, sc_.dt);
    model::State state = model::State::at_rest(system.size());
    integrator->reset(system, state);
    std::vector<double> seconds;
    for (long k = 1; k <= o_.timing_steps; ++k) {
      const Stopwatch clock;
      integrator->advance_to(static_cast<double>(k) * sc_.dt, state);
      seconds.push_back(clock.seconds());
    }
    return simulation::median(seconds);
  }

 private:
  const RoiSizeOptions& o_;
  const scenario::Scenario& sc_;
  const simulation::ScenarioModel& full_;
  std::ostream& log_;
  RoiNodeDofs evaluated_;  // the nodes where the error is measured
  std::vector<Vector> reference_;
};

}  // namespace

RoiSizeResults run_roi_size(const RoiSizeOptions& o, std::ostream& log) {
  if (!(o.max_error_mm > 0) || !std::isfinite(o.max_error_mm))
    throw InputError("roi-size: --max-error-mm must be positive (got " + number_text(o.max_error_mm) + ")");
  if (o.reductions.empty()) throw InputError("roi-size: no reduction to size");
  scenario::Scenario sc = scenario::read_scenario(o.scenario);
  if (!sc.roi || (sc.roi->kind != roi::RoiSpec::Kind::ball && sc.roi->kind != roi::RoiSpec::Kind::nearest))
    throw InputError(sc.file.string() +
                     ": roi-size needs an ROI target: [roi] kind = \"nearest\" (target_mm) or \"ball\" (center_mm)");
  const Vec3 target = sc.roi->center;
  if (!o.out.empty()) check_output_directory(o.out);
  scenario::Scenario full_scenario = sc;
  full_scenario.roi.reset();
  const auto full = simulation::build_scenario_model(full_scenario);

  RoiSizeResults results;
  results.target = target;
  results.free_nodes = static_cast<Index>(roi::free_nodes(full->mesh, *full->full.dofs).size());
  log << format(
      "roi-size: %s, %lld free nodes; ROI = the N nodes nearest (%g, %g, %g) mm; budget: max error <= %g mm at the "
      "scenario's ROI (%s) over %ld steps of %s at dt = %g s\n",
      sc.file.c_str(), static_cast<long long>(results.free_nodes), target.x() / mm, target.y() / mm, target.z() / mm,
      o.max_error_mm, sc.roi->describe().c_str(), sc.steps, sc.integrator.c_str(), sc.dt);
  Search search(o, sc, *full, log);
  results.full_step_s_median = search.step_median(full->system());
  for (const auto& reduction : o.reductions) results.rows.push_back(search.find(reduction, results.free_nodes));

  log << format("\nSmallest ROI with max error <= %g mm (full model: %lld free nodes, %.4f ms per step)\n", o.max_error_mm,
                static_cast<long long>(results.free_nodes), results.full_step_s_median * 1e3);
  log << format("  %-18s %7s %6s %15s %11s %9s %6s\n", "reduction", "nodes", "dofs", "peak max (mm)", "step (ms)", "vs full",
                "runs");
  for (const auto& r : results.rows) {
    if (!r.found) {
      log << format("  %-18s   none within the mesh\n", r.reduction.c_str());
      continue;
    }
    log << format("  %-18s %7lld %6lld %15.4f %11.4f %8.2fx %6d\n", r.reduction.c_str(), static_cast<long long>(r.nodes),
                  static_cast<long long>(r.dofs), r.peak_max_mm, r.step_s_median * 1e3,
                  r.step_s_median / results.full_step_s_median, r.evaluations);
  }
  if (!o.out.empty()) {
    io::CsvWriter csv(o.out / "roi_size.csv", "reduction,found,nodes,dofs,peak_max_mm,step_s_median,evaluations,max_error_mm");
    for (const auto& r : results.rows)
      csv.row(format("%s,%d,%lld,%lld,%.9g,%.6e,%d,%g", r.reduction.c_str(), r.found ? 1 : 0, static_cast<long long>(r.nodes),
                     static_cast<long long>(r.dofs), r.peak_max_mm, r.step_s_median, r.evaluations, o.max_error_mm));
    csv.close();
    log << "results: " << (o.out / "roi_size.csv").string() << '\n';
  }
  return results;
}

}  // namespace roifem::experiments
