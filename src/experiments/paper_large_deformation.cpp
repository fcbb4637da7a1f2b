// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/paper_large_deformation.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <ostream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "condensation/reduced_model.hpp"
#include "experiments/paper_model.hpp"
#include "experiments/paper_report.hpp"
#include "experiments/roi_error.hpp"
#include "integrators/trapezoid.hpp"
#include "io/plots.hpp"
#include "io/result_table.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"
#include "model/hyperelastic_force.hpp"
#include "simulation/run_loop.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::experiments {

namespace {

std::string drive_name(PaperDrive drive) { return drive == PaperDrive::spatulas ? "spatulas" : "forces"; }

double peak_of(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

constexpr std::array measured_models{LargeDeformationModel::hybrid, LargeDeformationModel::linear_condensed,
                                     LargeDeformationModel::full_linear};

/// One setup's two condensed models and its ROI nodes in both numberings.
struct HybridSetup {
  std::string name;
  std::unique_ptr<condensation::ReducedModel> linear;  ///< static condensation of the linear model
  model::SecondOrderSystem hybrid;                     ///< the same with the hybrid ROI's law
  model::ToolSet linear_tools, hybrid_tools;           ///< the spatulas, reduced numbering (none: forces)
  RoiNodeDofs in_reduced, in_full;                     ///< the ROI nodes: reduced against full, full against full
};

/// A run's states and the tools' forces at steps 1..steps (fewer where it stopped), its step times
/// and counters.
struct Trajectory {
  std::vector<Vector> u, forces;
  std::vector<double> step_s;
  integrators::Stats stats;
  std::string stopped;  ///< why it stopped short, named (empty: it ran every step)
};

/// A step whose Newton iteration does not converge, or that inverts an element, stops that run
/// (named, its steps so far kept) and not the experiment: that a model cannot take the load at the
/// paper's dt is one of the results.
Trajectory run_trapezoid(const model::SecondOrderSystem& system, const model::ToolSet& tools, double dt, long steps,
                         const std::string& label, std::ostream& log) {
  integrators::Trapezoid trapezoid(dt);
  model::State state = model::State::at_rest(system.size());
  trapezoid.reset(system, state);
  Trajectory t;
  try {
    simulation::run(trapezoid, state, dt, steps, {[&](long, const model::State& s, double seconds) {
                      t.u.push_back(s.u);
                      t.step_s.push_back(seconds);
                      if (!tools.empty()) t.forces.push_back(tools.forces(s.u, s.t));
                    }},
                    label, &log);
  } catch (const SolverError& e) {
    t.stopped = label + ": " + e.what();
  } catch (const ModelError& e) {
    t.stopped = label + ": " + e.what();
  }
  t.stats = trapezoid.stats();
  if (!t.stopped.empty()) log << "  stopped: " << t.stopped << '\n' << std::flush;
  return t;
}

/// The model's error against the reference, step by step, on `nodes`.
void measure_errors(const Trajectory& run, const Trajectory& reference, const RoiNodeDofs& nodes, LargeDeformationCurve& c) {
  for (std::size_t k = 0; k < std::min(run.u.size(), reference.u.size()); ++k) {
    const RoiError e = roi_error(nodes, run.u[k], reference.u[k]);
    c.mean_mm.push_back(e.mean / mm);
    c.max_mm.push_back(e.max / mm);
    if (run.forces.empty()) continue;
    const auto [error, largest] = force_error_mN(run.forces[k], reference.forces[k]);
    c.force_err_mN.push_back(error);
    c.force_full_mN.push_back(largest);
  }
}

LargeDeformationTiming timing_of(PaperDrive drive, std::string model, Index nodes, Index dofs, const Trajectory& run) {
  return {
      .drive = drive,
      .model = std::move(model),
      .nodes = nodes,
      .dofs = dofs,
      .step_s_median = run.step_s.empty() ? 0.0 : simulation::median(run.step_s),
      .step_s_p99 = run.step_s.empty() ? 0.0 : simulation::percentile(run.step_s, 0.99),
      .newton_per_step = static_cast<double>(run.stats.nonlinear_iterations) / static_cast<double>(std::max(1L, run.stats.steps)),
      .indefinite_steps = run.stats.indefinite_steps};
}

/// `roifem paper --material-model neo-hookean` as named phases, one drive at a time.
class LargeDeformationPaper {
 public:
  LargeDeformationPaper(const PaperOptions& options, std::ostream& log) : o_(options), log_(log) {}
  LargeDeformationResults run(const std::vector<PaperDrive>& drives);

 private:
  void build_models(PaperDrive drive);  ///< the neo-Hookean and the linear full model under the drive
  void build_setups();                  ///< each setup's linear condensation and hybrid
  void measure(LargeDeformationDrive& d);
  void measure_budget(LargeDeformationDrive& d);
  void report(const LargeDeformationDrive& d) const;
  void write(const LargeDeformationResults& results) const;

  const PaperOptions& o_;
  std::ostream& log_;
  mesh::TetMesh mesh_;
  std::unique_ptr<PaperModel> nonlinear_, linear_;
  std::vector<HybridSetup> setups_;
  /// Per setup and ramp: the linear condensed model against the full linear one (the paper's own
  /// error), for the budget's reduction column.
  std::vector<std::vector<ErrorCurve>> reduction_;
};

LargeDeformationResults LargeDeformationPaper::run(const std::vector<PaperDrive>& drives) {
  if (!(o_.dt > 0) || o_.steps <= 0 || !(o_.opening_mm > 0))
    throw InputError("paper: dt, --steps and --opening-mm must be positive");
  check_output_directory(o_.out);
  mesh_ = mesh::read_mesh(o_.mesh);
  mesh::check_mesh(mesh_);
  LargeDeformationResults results{.dt = o_.dt, .opening_mm = o_.opening_mm, .ramps_s = o_.ramps_s, .drives = {}};
  for (const PaperDrive drive : drives) {
    build_models(drive);
    build_setups();
    LargeDeformationDrive& d = results.drives.emplace_back();
    d.drive = drive;
    d.force_N = linear_->force_N;
    measure(d);
    if (drive == PaperDrive::forces && o_.error_budget) measure_budget(d);
    report(d);
  }
  write(results);
  return results;
}

void LargeDeformationPaper::build_models(PaperDrive drive) {
  fem::Material material = fem::material_preset(o_.material);
  material.model = fem::MaterialModel::linear;
  linear_ = build_paper_model(mesh_, material, o_.fixed_set, drive, o_.opening_mm);
  material.model = fem::MaterialModel::neo_hookean;
  nonlinear_ = build_paper_model(mesh_, material, o_.fixed_set, drive, o_.opening_mm);
  log_ << format("\npaper at large deformation, driven by %s: %s, %lld nodes, material '%s' (neo-hookean: %s)\n",
                 drive_name(drive).c_str(), o_.mesh.c_str(), static_cast<long long>(mesh_.num_nodes()), o_.material.c_str(),
                 nonlinear_->full.system.internal_force->describe().c_str());
  if (drive == PaperDrive::forces)
    log_ << format("  %.4g mN on each wall: the linear model's static opening widens by %.1f mm\n", linear_->force_N * 1e3,
                   o_.opening_mm);
  else
    log_ << format(
        "  two spatulas move the walls %.2f mm apart each (%.1f mm in all); the linear model holds them at rest by %.4g mN\n",
        o_.opening_mm / 2, o_.opening_mm, linear_->force_N * 1e3);
}

void LargeDeformationPaper::build_setups() {
  setups_.clear();
  const fem::DofMap& dofs = *linear_->full.dofs;
  const auto static_condensation = condensation::parse_reduction("static");
  for (std::size_t k = 0; k < o_.setup_nodes.size(); ++k) {
    const roi::RoiSpec spec{
        .kind = roi::RoiSpec::Kind::nearest, .center = o_.roi_target_mm * mm, .radius = 0, .count = o_.setup_nodes[k], .set = {}};
    const roi::Partition partition = roi::partition_dofs(linear_->full.system.K, dofs, select_setup_nodes(*linear_, spec));
    HybridSetup s;
    s.name = "setup" + std::to_string(k + 1);
    s.linear = std::make_unique<condensation::ReducedModel>(linear_->full.system, partition, dofs, static_condensation);
    s.hybrid = s.linear->system();
    s.hybrid.internal_force = model::hybrid_roi_force(mesh_, dofs, nonlinear_->full.materials, fem::Element::tet4, partition,
                                                      s.hybrid.K, nonlinear_->full.tools.tools(), &s.hybrid.K_split);
    s.in_reduced = roi_node_dofs(partition, dofs);
    s.in_full = full_node_dofs(partition.roi_nodes, dofs);
    if (!linear_->full.tools.empty()) {
      s.linear_tools = simulation::tools_in_reduced(linear_->full, partition, s.hybrid.size());
      s.hybrid_tools = s.linear_tools.with_law(s.hybrid.internal_force);
    }
    log_ << format("  %s: %zu ROI nodes, %lld dofs; %s\n", s.name.c_str(), partition.roi_nodes.size(),
                   static_cast<long long>(s.hybrid.size()), s.hybrid.internal_force->describe().c_str());
    setups_.push_back(std::move(s));
  }
}

void LargeDeformationPaper::measure(LargeDeformationDrive& d) {
  const model::FemModel& nl = nonlinear_->full;
  const model::FemModel& lin = linear_->full;
  reduction_.assign(setups_.size(), {});
  for (const double ramp_s : o_.ramps_s) {
    const model::Ramp ramp{ramp_s};
    const std::string at = format(", ramp %.1f s", ramp_s);
    const Trajectory reference = run_trapezoid(model::with_ramp(nl.system, ramp), nl.tools.with_ramp(ramp), o_.dt, o_.steps,
                                               "full neo-hookean" + at, log_);
    const Trajectory full_linear =
        run_trapezoid(model::with_ramp(lin.system, ramp), lin.tools.with_ramp(ramp), o_.dt, o_.steps, "full linear" + at, log_);
    for (const Trajectory* t : {&reference, &full_linear})
      if (!t->stopped.empty()) d.stopped.push_back(t->stopped);
    const bool first_ramp = ramp_s == o_.ramps_s.front();
    if (first_ramp) {
      d.timing.push_back(timing_of(d.drive, "full neo-hookean", mesh_.num_nodes(), nl.system.size(), reference));
      d.timing.push_back(timing_of(d.drive, "full linear", mesh_.num_nodes(), lin.system.size(), full_linear));
    }
    for (std::size_t si = 0; si < setups_.size(); ++si) {
      const HybridSetup& s = setups_[si];
      const Trajectory hybrid = run_trapezoid(model::with_ramp(s.hybrid, ramp), s.hybrid_tools.with_ramp(ramp), o_.dt, o_.steps,
                                              s.name + " hybrid" + at, log_);
      const Trajectory condensed = run_trapezoid(model::with_ramp(s.linear->system(), ramp), s.linear_tools.with_ramp(ramp),
                                                 o_.dt, o_.steps, s.name + " linear condensed" + at, log_);
      for (const Trajectory* t : {&hybrid, &condensed})
        if (!t->stopped.empty()) d.stopped.push_back(t->stopped);
      const auto nodes = static_cast<Index>(s.in_reduced.in_reduced.size());
      if (first_ramp) {
        d.timing.push_back(timing_of(d.drive, s.name + " hybrid", nodes, s.hybrid.size(), hybrid));
        d.timing.push_back(timing_of(d.drive, s.name + " linear", nodes, s.hybrid.size(), condensed));
      }
      for (const LargeDeformationModel model : measured_models) {
        LargeDeformationCurve& c = d.curves.emplace_back();
        c.drive = d.drive;
        c.setup = s.name;
        c.model = model;
        c.ramp_s = ramp_s;
        if (model == LargeDeformationModel::hybrid) measure_errors(hybrid, reference, s.in_reduced, c);
        if (model == LargeDeformationModel::linear_condensed) measure_errors(condensed, reference, s.in_reduced, c);
        if (model == LargeDeformationModel::full_linear) measure_errors(full_linear, reference, s.in_full, c);
      }
      if (si == 0 && !reference.u.empty()) {
        const Vector zero = Vector::Zero(reference.u.front().size());
        for (const Vector& u : reference.u) d.peak_mm = std::max(d.peak_mm, roi_error(s.in_full, zero, u).max / mm);
      }
      LargeDeformationCurve reduction;
      measure_errors(condensed, full_linear, s.in_reduced, reduction);
      reduction_[si].push_back({reduction.mean_mm, reduction.max_mm});
    }
  }
  // HybridSetup-major, as the linear paper's curves: setup, model, ramp.
  std::stable_sort(d.curves.begin(), d.curves.end(), [](const LargeDeformationCurve& a, const LargeDeformationCurve& b) {
    return a.setup != b.setup ? a.setup < b.setup : a.model < b.model;
  });
}

/// The curves of one model, setup-major then ramp, in the findings' order.
std::vector<PaperCurve> paper_curves(const LargeDeformationDrive& d, LargeDeformationModel model) {
  std::vector<PaperCurve> curves;
  for (const auto& c : d.curves)
    if (c.model == model) curves.push_back(c.as_paper_curve());
  return curves;
}

/// The step costs the findings compare: the full neo-Hookean model's, then each setup's `kind`.
std::vector<double> step_costs(const LargeDeformationDrive& d, const std::string& kind) {
  std::vector<double> step_s;
  for (const auto& t : d.timing)
    if (t.model == "full neo-hookean" || t.model.ends_with(" " + kind)) step_s.push_back(t.step_s_median);
  return step_s;
}

void LargeDeformationPaper::measure_budget(LargeDeformationDrive& d) {
  BudgetInput in{.full = &linear_->full,
                 .fixed_sets = {o_.fixed_set},
                 .force_N = d.force_N,
                 .dt = o_.dt,
                 .steps = o_.steps,
                 .ramps_s = o_.ramps_s,
                 .setups = {},
                 .reduction = reduction_,
                 .model_dynamic = {},
                 .hybrid = {}};
  for (const HybridSetup& s : setups_) {
    in.setups.emplace_back(s.name, s.linear->partition().roi_nodes);
    auto& dynamic = in.model_dynamic.emplace_back();
    auto& hybrid = in.hybrid.emplace_back();
    for (const auto& c : d.curves)
      if (c.setup == s.name && c.model == LargeDeformationModel::full_linear)
        dynamic.push_back({c.mean_mm, c.max_mm});
      else if (c.setup == s.name && c.model == LargeDeformationModel::hybrid)
        hybrid.push_back({c.mean_mm, c.max_mm});
  }
  d.budget = measure_error_budget(in, o_.budget, o_.out, log_);
}

void LargeDeformationPaper::report(const LargeDeformationDrive& d) const {
  const std::size_t n_ramps = o_.ramps_s.size();
  log_ << format(
      "\nFindings (Hansen & Larsen 1998, Section 5) at large deformation, driven by %s: the hybrid ROI against "
      "the full neo-Hookean model\n",
      drive_name(d.drive).c_str());
  print_findings(paper_curves(d, LargeDeformationModel::hybrid), n_ramps, o_.steps, step_costs(d, "hybrid"), log_);
  for (const auto& c : d.curves)
    if (static_cast<long>(c.max_mm.size()) < o_.steps)
      log_ << format("  [--] %s %s, ramp %.1f s, stopped at step %zu (below): a finding that needs it is not measured\n",
                     c.setup.c_str(), std::string(model_name(c.model)).c_str(), c.ramp_s, c.max_mm.size() + 1);
  log_ << "The paper's own model (linear, condensed) against the full neo-Hookean model:\n";
  print_findings(paper_curves(d, LargeDeformationModel::linear_condensed), n_ramps, o_.steps, step_costs(d, "linear"), log_);

  log_ << format(
      "\nThe three models against the full neo-Hookean one, on each setup's ROI nodes (mm: peak over the run of the "
      "largest nodal error / steady mean after step 100); the reference peaks at %.3f mm over setup 1's ROI\n",
      d.peak_mm);
  log_ << format("  %-7s %5s  %17s  %17s  %17s\n", "setup", "ramp", "hybrid", "linear condensed", "full linear");
  for (std::size_t k = 0; k < d.curves.size(); k += 3 * n_ramps)
    for (std::size_t r = 0; r < n_ramps; ++r) {
      std::string line = format("  %-7s %4.1fs", d.curves[k].setup.c_str(), d.curves[k + r].ramp_s);
      for (std::size_t m = 0; m < 3; ++m) {
        const PaperCurve c = d.curves[k + m * n_ramps + r].as_paper_curve();
        line += c.mean_mm.size() > 100 ? format("  %7.3f / %7.4f", peak_of(c.max_mm), steady_mean(c))
                                       : format("  %7.3f / %7s", peak_of(c.max_mm), "-");
      }
      log_ << line << '\n';
    }

  log_ << format("\nTable 2 at large deformation (trapezoidal rule, dt = %g s; Newton on the neo-Hookean models; ramp %.1f s)\n",
                 o_.dt, o_.ramps_s.front());
  log_ << format("  %-24s %6s %6s %12s %11s %13s %10s\n", "model", "nodes", "dofs", "step (ms)", "p99 (ms)", "Newton/step",
                 "vs full");
  for (const auto& t : d.timing) {
    const double full = d.timing.front().step_s_median;
    log_ << format("  %-24s %6lld %6lld %12.3f %11.3f %13s %10s", t.model.c_str(), static_cast<long long>(t.nodes),
                   static_cast<long long>(t.dofs), t.step_s_median * 1e3, t.step_s_p99 * 1e3,
                   t.newton_per_step > 0 ? format("%.2f", t.newton_per_step).c_str() : "-",
                   full > 0 && t.step_s_median > 0 ? format("%.2fx", full / t.step_s_median).c_str() : "- (no step)");
    log_ << (t.indefinite_steps > 0 ? format("  (%ld steps' Newton matrices indefinite: by LU)\n", t.indefinite_steps) : "\n");
  }
  log_ << "  (medians of per-step wall time on this machine over the run at the first ramp; vs full: against the full "
          "neo-Hookean model)\n";

  if (d.drive == PaperDrive::spatulas) {
    log_ << "\nThe force the surgeon feels: each spatula's force against the full neo-Hookean model's (peak error in mN, and "
            "% of the reference's peak force)\n";
    log_ << format("  %-7s %5s %14s  %18s  %18s  %18s\n", "setup", "ramp", "full peak (mN)", "hybrid", "linear condensed",
                   "full linear");
    for (std::size_t k = 0; k < d.curves.size(); k += 3 * n_ramps)
      for (std::size_t r = 0; r < n_ramps; ++r) {
        const auto& first = d.curves[k + r];
        std::string line = format("  %-7s %4.1fs %14.3f", first.setup.c_str(), first.ramp_s, peak_of(first.force_full_mN));
        for (std::size_t m = 0; m < 3; ++m) {
          const auto& c = d.curves[k + m * n_ramps + r];
          line += peak_of(c.force_full_mN) > 0 ? format("  %9.3f (%5.2f%%)", peak_of(c.force_err_mN),
                                                        100 * peak_of(c.force_err_mN) / peak_of(c.force_full_mN))
                                               : format("  %18s", "- (no step)");
        }
        log_ << line << '\n';
      }
  }
  if (d.budget) print_error_budget(*d.budget, log_);
  if (!d.stopped.empty()) {
    log_ << "\nRuns that stopped short (their figures cover the steps they took):\n";
    for (const auto& why : d.stopped) log_ << "  " << why << '\n';
  }
  log_ << std::flush;
}

/// One step of one curve: a row of large_deformation.csv.
struct CurveStep {
  const LargeDeformationCurve* curve = nullptr;
  long step = 0;
  double time_s = 0;
};

double at_step(const std::vector<double>& series, const CurveStep& s) { return series[static_cast<std::size_t>(s.step - 1)]; }

using io::Cell;
using io::Column;

const std::array<Column<CurveStep>, 10> large_deformation_columns{{
    {"drive", "forces or spatulas", [](const CurveStep& s) -> Cell { return drive_name(s.curve->drive); }},
    {"setup", "setup1, setup2, ...", [](const CurveStep& s) -> Cell { return s.curve->setup; }},
    {"model", "hybrid, linear condensed or full linear: measured against the full neo-Hookean model",
     [](const CurveStep& s) -> Cell { return std::string(model_name(s.curve->model)); }},
    {"ramp_s", "the load's (or the spatulas') ramp time (s)", [](const CurveStep& s) -> Cell { return s.curve->ramp_s; }, "%g"},
    {"step", "the step, 1..steps", [](const CurveStep& s) -> Cell { return s.step; }},
    {"time_s", "the step's time (s)", [](const CurveStep& s) -> Cell { return s.time_s; }, "%.4f"},
    {"mean_mm", "the mean over the setup's ROI nodes of |u_model - u_neo-hookean| (mm)",
     [](const CurveStep& s) -> Cell { return at_step(s.curve->mean_mm, s); }, "%.9g"},
    {"max_mm", "the largest over the setup's ROI nodes of |u_model - u_neo-hookean| (mm)",
     [](const CurveStep& s) -> Cell { return at_step(s.curve->max_mm, s); }, "%.9g"},
    {"force_full_mN", "spatulas: the larger of the two spatulas' force in the full neo-Hookean model (mN)",
     [](const CurveStep& s) -> Cell {
       return s.curve->force_full_mN.empty() ? Cell() : Cell(at_step(s.curve->force_full_mN, s));
     },
     "%.9g"},
    {"force_err_mN", "spatulas: the larger of the two spatulas' |F_model - F_neo-hookean| (mN)",
     [](const CurveStep& s) -> Cell { return s.curve->force_err_mN.empty() ? Cell() : Cell(at_step(s.curve->force_err_mN, s)); },
     "%.9g"},
}};

const std::array<Column<LargeDeformationTiming>, 9> large_deformation_timing_columns{{
    {"drive", "forces or spatulas", [](const LargeDeformationTiming& t) -> Cell { return drive_name(t.drive); }},
    {"model", "full neo-hookean, full linear, setupN hybrid, setupN linear",
     [](const LargeDeformationTiming& t) -> Cell { return t.model; }},
    {"nodes", "the model's nodes (a setup: its ROI's)",
     [](const LargeDeformationTiming& t) -> Cell { return static_cast<long>(t.nodes); }},
    {"dofs", "the integrated system's degrees of freedom",
     [](const LargeDeformationTiming& t) -> Cell { return static_cast<long>(t.dofs); }},
    {"step_s_median", "the median step cost of the trapezoidal rule, Newton included (s)",
     [](const LargeDeformationTiming& t) -> Cell { return t.step_s_median; }, "%.6e"},
    {"step_s_p99", "the 99th percentile of the step cost (s)",
     [](const LargeDeformationTiming& t) -> Cell { return t.step_s_p99; }, "%.6e"},
    {"newton_per_step", "Newton iterations per step (0: a linear model, one solve per step)",
     [](const LargeDeformationTiming& t) -> Cell { return t.newton_per_step; }, "%.4f"},
    {"indefinite_steps", "steps whose Newton matrix was indefinite (solved by LU)",
     [](const LargeDeformationTiming& t) -> Cell { return t.indefinite_steps; }},
    {"frame_rate_hz", "1 / step_s_median (Hz)", [](const LargeDeformationTiming& t) -> Cell { return 1.0 / t.step_s_median; },
     "%.1f"},
}};

void LargeDeformationPaper::write(const LargeDeformationResults& results) const {
  std::vector<CurveStep> steps;
  std::vector<LargeDeformationTiming> timing;
  for (const auto& d : results.drives) {
    for (const auto& c : d.curves)
      for (std::size_t k = 0; k < c.max_mm.size(); ++k)
        steps.push_back({&c, static_cast<long>(k + 1), static_cast<double>(k + 1) * results.dt});
    timing.insert(timing.end(), d.timing.begin(), d.timing.end());
    if (d.budget) write_error_budget_csv(*d.budget, results.dt, o_.out);
  }
  io::write_csv(o_.out / "large_deformation.csv", std::span<const Column<CurveStep>>(large_deformation_columns), steps);
  io::write_csv(o_.out / "large_deformation_timing.csv",
                std::span<const Column<LargeDeformationTiming>>(large_deformation_timing_columns), timing);
  std::string files = (o_.out / "large_deformation.csv").string() + ", " + (o_.out / "large_deformation_timing.csv").string();
  for (const auto& d : results.drives)
    if (d.budget) files += ", " + (o_.out / "error_budget.csv").string();
  if (o_.plots && io::run_plot_script("plot_large_deformation.py", o_.out, log_))
    files += ", " + (o_.out / "large_deformation.png").string();
  log_ << "\nresults: " << files << '\n';
}

}  // namespace

std::string_view model_name(LargeDeformationModel model) {
  switch (model) {
    case LargeDeformationModel::hybrid:
      return "hybrid";
    case LargeDeformationModel::linear_condensed:
      return "linear condensed";
    case LargeDeformationModel::full_linear:
      return "full linear";
  }
  return "?";
}

PaperCurve LargeDeformationCurve::as_paper_curve() const {
  return {.setup = setup,
          .static_condensation = model != LargeDeformationModel::full_linear,
          .reduction = std::string(model_name(model)),
          .ramp_s = ramp_s,
          .mean_mm = mean_mm,
          .max_mm = max_mm,
          .force_err_mN = force_err_mN,
          .force_full_mN = force_full_mN};
}

LargeDeformationResults run_paper_large_deformation(const PaperOptions& options, const std::vector<PaperDrive>& drives,
                                                    std::ostream& log) {
  return LargeDeformationPaper(options, log).run(drives);
}

}  // namespace roifem::experiments
