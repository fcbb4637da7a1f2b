// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/paper_experiment.hpp"

#include "mesh/brain_mesh.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <ostream>
#include <set>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/number_text.hpp"
#include "common/timer.hpp"
#include "condensation/reduced_model.hpp"
#include "experiments/paper_model.hpp"
#include "experiments/paper_report.hpp"
#include "experiments/roi_error.hpp"
#include "fem/static_solve.hpp"
#include "integrators/trapezoid.hpp"
#include "io/hdf5_file.hpp"
#include "io/plots.hpp"
#include "io/xdmf.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"
#include "model/fem_model.hpp"
#include "simulation/run_loop.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::experiments {

namespace {

struct Setup {
  std::string name;
  condensation::Reduction reduction;
  std::string label;  ///< reduction.label()
  std::unique_ptr<condensation::ReducedModel> condensation;
  RoiNodeDofs node_dofs;
  model::ToolSet tools;  ///< the spatulas in the reduced numbering (none when forces drive)
  double setup_s = 0;
};

/// Per-step wall times of `steps` steps of each system after a short warm-up (the load ramp still
/// rising). The systems take turns in blocks of 50 steps, so that the machine's slow drifts (other
/// work, clock changes) fall on every system alike and the ratios between them hold; within a block
/// a system runs from a warm cache, as it would alone.
std::vector<std::vector<double>> time_steps(const std::vector<const model::SecondOrderSystem*>& systems, double dt, long steps) {
  constexpr long block = 50;
  std::vector<integrators::Trapezoid> trapezoids;
  std::vector<model::State> states;
  std::vector<std::vector<double>> seconds(systems.size());
  trapezoids.reserve(systems.size());
  states.reserve(systems.size());
  for (std::size_t m = 0; m < systems.size(); ++m) {
    const auto& system = *systems[m];
    trapezoids.emplace_back(dt);
    states.push_back(model::State::at_rest(system.size()));
    trapezoids[m].reset(system, states[m]);
    for (int k = 0; k < 20; ++k) trapezoids[m].step(states[m]);
    seconds[m].reserve(static_cast<std::size_t>(steps));
  }
  for (long done = 0; done < steps; done += block)
    for (std::size_t m = 0; m < systems.size(); ++m)
      for (long k = done; k < std::min(steps, done + block); ++k) {
        const Stopwatch clock;
        trapezoids[m].step(states[m]);
        seconds[m].push_back(clock.seconds());
      }
  return seconds;
}

/// Displacement fields for results.h5 and the XDMF series that play them (full, and setup 1 with
/// the paper's reduction), every field_every steps of the first ramp.
struct FieldRecord {
  io::XdmfSeries full_series, roi_series;
  std::vector<std::pair<std::string, std::vector<double>>> fields;
  void add(io::XdmfSeries& series, const std::string& name, const model::State& s, std::vector<double> field) {
    fields.emplace_back(name, std::move(field));
    series.times.push_back(s.t);
    series.fields.push_back("/" + name);
  }
};

/// Every node's displacement (mm, N x 3 row-major), the spatulas' nodes where their paths put them.
std::vector<double> field_mm(const PaperModel& m, const model::ToolSet& tools, const Vector& u_free, double t) {
  const Vector u = m.full.displacement(u_free, tools, t) / mm;
  return {u.data(), u.data() + u.size()};
}

/// The full model's run under one ramp: displacements and (spatulas) tool forces per step.
struct Reference {
  std::vector<Vector> u, forces;
};

/// `roifem paper` as a list of phases (run()), each a member that reads and fills the
/// experiment's state: the model, the setups, the field record, the results.
class PaperExperiment {
 public:
  PaperExperiment(const PaperOptions& options, std::ostream& log) : o_(options), log_(log) {}
  PaperResults run();

 private:
  void check_options() const;
  void build_model();       ///< the mesh and the full model under the drive (forces scaled to the opening, or spatulas)
  void build_setups();      ///< every setup reduced by every reduction, setup-major
  void measure_accuracy();  ///< each ramp: the full model against each setup
  Reference run_reference(double ramp);
  PaperCurve run_setup(const Setup& setup, double ramp, const Reference& reference, bool record_fields);
  void measure_speed();  ///< Table 2 and the reductions' step costs, the models taking turns
  void write_results() const;
  void write_results_h5() const;
  /// Runs a plot script on the output directory and names what it drew.
  void plot(const char* script, const std::vector<std::string>& pngs) const;
  void measure_error_budget();  ///< space, time, reduction and model error (forces drive)

  const PaperOptions& o_;
  std::ostream& log_;
  PaperResults results_;
  std::unique_ptr<PaperModel> model_;
  std::vector<Setup> setups_;
  FieldRecord record_;
};

PaperResults PaperExperiment::run() {
  check_options();
  results_.dt = o_.dt;
  results_.ramps_s = o_.ramps_s;
  build_model();
  build_setups();
  measure_accuracy();
  measure_speed();
  write_results();
  print_paper_report(results_, log_);  // the findings, Table 2, the reductions (and the spatulas' forces)
  log_ << std::flush;
  std::vector<std::string> pngs{"mean_error.png", "max_error.png", "step_time.png", "reductions.png"};
  if (o_.drive == PaperDrive::spatulas) pngs.emplace_back("force_error.png");
  plot("plot_paper.py", pngs);
  // The budget last: its reference takes most of the run's time (cached for the next run).
  if (o_.error_budget && o_.drive == PaperDrive::forces) {
    measure_error_budget();
    write_error_budget_csv(*results_.budget, o_.dt, o_.out);
    print_error_budget(*results_.budget, log_);
    plot("plot_error_budget.py", {"error_budget.png"});
  }
  log_ << "results: " << (o_.out / "errors.csv").string() << ", " << (o_.out / "timing.csv").string() << ", "
       << (o_.out / "reductions.csv").string() << ", "
       << (o_.drive == PaperDrive::spatulas ? (o_.out / "force_errors.csv").string() + ", " : "")
       << (results_.budget ? (o_.out / "error_budget.csv").string() + ", " : "") << (o_.out / "results.h5").string()
       << " (ParaView: results.xdmf, results_setup1.xdmf)\n";
  return results_;
}

void PaperExperiment::check_options() const {
  const PaperOptions& o = o_;
  if (!(o.dt > 0)) throw InputError("paper: dt = " + number_text(o.dt) + " s must be positive");
  if (o.steps <= 0) throw InputError("paper: steps must be positive");
  if (o.timing_steps < 1) throw InputError("paper: timing steps must be positive");
  if (!(o.opening_mm > 0)) throw InputError("paper: --opening-mm must be positive");
  if (o.reductions.empty() || !o.reductions.front().is_static_condensation())
    throw InputError("paper: the first reduction must be static condensation (the paper's)");
  check_output_directory(o.out);
}

void PaperExperiment::build_model() {
  const PaperOptions& o = o_;
  PaperResults& results = results_;
  std::ostream& log = log_;
  mesh::TetMesh mesh = mesh::read_mesh(o.mesh);
  mesh::check_mesh(mesh);
  if (o.drive == PaperDrive::forces && o.error_budget && o.budget.reference_nodes > 0) {
    // The budget's space error regenerates the ellipsoid brain finer: refuse another shape now,
    // not after the whole run.
    const mesh::BrainShape shape;
    const Vec3 hi = mesh.nodes.rowwise().maxCoeff() / mm, lo = mesh.nodes.rowwise().minCoeff() / mm;
    const Vec3 expected(shape.semi_axis_x, shape.semi_axis_y, shape.semi_axis_z);
    if (((hi - expected).cwiseAbs().array() > 0.05 * expected.array()).any() ||
        ((lo + expected).cwiseAbs().array() > 0.05 * expected.array()).any())
      throw InputError(
          format("%s spans [%.1f, %.1f] x [%.1f, %.1f] x [%.1f, %.1f] mm, not the generated ellipsoid brain that "
                 "the error budget's space error refines; add --no-error-budget (or --budget-nodes 0)",
                 o.mesh.c_str(), lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), hi.z()));
  }
  results.drive = o.drive;
  results.opening_mm = o.opening_mm;
  auto m = build_paper_model(mesh, fem::material_preset(o.material), o.fixed_set, o.drive, o.opening_mm);
  results.force_N = m->force_N;
  const fem::DofMap& dofs = *m->full.dofs;
  log << format("paper experiment: %s, %lld nodes (%lld free dofs), material '%s'\n", o.mesh.c_str(),
                static_cast<long long>(m->mesh.num_nodes()), static_cast<long long>(dofs.num_free()), o.material.c_str());
  if (o.drive == PaperDrive::forces)
    log << format("  force %.4g mN on each wall of the opening (x: -left, +right) widens it statically by %.1f mm\n",
                  results.force_N * 1e3, o.opening_mm);
  else
    log << format(
        "  two spatulas hold the walls' nodes (%zu and %zu) and move them %.2f mm apart each (x: -left, +right): "
        "%.1f mm in all, held at rest by %.4g mN\n",
        m->full.tools.tools()[0].nodes.size(), m->full.tools.tools()[1].nodes.size(), o.opening_mm / 2, o.opening_mm,
        results.force_N * 1e3);
  for (const auto& warning : m->full.warnings) log << "  warning: " << warning << '\n';
  model_ = std::move(m);
}

void PaperExperiment::build_setups() {
  const PaperOptions& o = o_;
  const PaperModel& m = *model_;
  PaperResults& results = results_;
  std::ostream& log = log_;
  const fem::DofMap& dofs = *m.full.dofs;
  std::vector<Setup>& setups = setups_;
  for (std::size_t k = 0; k < o.setup_nodes.size(); ++k) {
    const roi::RoiSpec spec{
        .kind = roi::RoiSpec::Kind::nearest, .center = o.roi_target_mm * mm, .radius = 0, .count = o.setup_nodes[k], .set = {}};
    const auto partition = roi::partition_dofs(m.full.system.K, dofs, select_setup_nodes(m, spec));
    std::set<int> interface_nodes;
    for (Index i : partition.interface)
      interface_nodes.insert(static_cast<int>(dofs.full_dof(partition.d[static_cast<std::size_t>(i)]) / 3));
    results.interface_nodes.push_back(static_cast<Index>(interface_nodes.size()));
    log << format("  setup%zu: ROI = %s: %zu dofs, %zu interface nodes, %zu static dofs", k + 1, spec.describe().c_str(),
                  partition.d.size(), interface_nodes.size(), partition.s.size());
    if (const Index held = spec.count - static_cast<Index>(partition.roi_nodes.size()); held > 0)
      log << format(" (%lld of its nodes held by the spatulas)", static_cast<long long>(held));
    log << "\n";
    for (const auto& reduction : o.reductions) {
      Setup s;
      s.name = "setup" + std::to_string(k + 1);
      s.reduction = reduction;
      s.label = reduction.label();
      Stopwatch clock;
      // A POD basis learns from the paper's own step and length.
      s.condensation =
          std::make_unique<condensation::ReducedModel>(m.full.system, partition, dofs, reduction.trained_on(o.dt, o.steps));
      s.setup_s = clock.seconds();
      s.node_dofs = roi_node_dofs(partition, dofs);
      if (!m.full.tools.empty()) s.tools = simulation::tools_in_reduced(m.full, partition, s.condensation->system().size());
      log << format("    %-18s %4lld dofs, reduced in %.3f s", s.label.c_str(),
                    static_cast<long long>(s.condensation->system().size()), s.setup_s);
      if (s.condensation->num_modes() > 0)
        log << format(" (fixed-interface modes %.2f to %.2f rad/s)", s.condensation->mode_frequencies()[0],
                      s.condensation->mode_frequencies()[s.condensation->num_modes() - 1]);
      log << "\n";
      setups.push_back(std::move(s));
    }
  }
}

Reference PaperExperiment::run_reference(double ramp) {
  const PaperOptions& o = o_;
  const PaperModel& m = *model_;
  FieldRecord& record = record_;
  model::SecondOrderSystem system = m.full.system;
  system.load = m.full.system.load.with_ramp(model::Ramp{ramp});
  const model::ToolSet tools = m.full.tools.with_ramp(model::Ramp{ramp});
  Reference reference;
  integrators::Trapezoid trapezoid(o.dt);
  model::State state = model::State::at_rest(system.size());
  trapezoid.reset(system, state);
  simulation::run(trapezoid, state, o.dt, o.steps, {[&](long k, const model::State& s, double) {
                    reference.u.push_back(s.u);
                    if (!tools.empty()) reference.forces.push_back(tools.forces(s.u, s.t));
                    if (ramp == o.ramps_s.front() && k % o.field_every == 0)
                      record.add(record.full_series, format("fields/full/displacement_mm_%04ld", k), s,
                                 field_mm(m, tools, s.u, s.t));
                  }},
                  format("full model, ramp %.1f s", ramp));
  return reference;
}

PaperCurve PaperExperiment::run_setup(const Setup& setup, double ramp, const Reference& reference, bool record_fields) {
  const PaperOptions& o = o_;
  const PaperModel& m = *model_;
  FieldRecord& record = record_;
  model::SecondOrderSystem reduced = setup.condensation->system();
  reduced.load = reduced.load.with_ramp(model::Ramp{ramp});
  const model::ToolSet tools = setup.tools.with_ramp(model::Ramp{ramp});
  PaperCurve curve{.setup = setup.name,
                   .static_condensation = setup.reduction.is_static_condensation(),
                   .reduction = setup.label,
                   .ramp_s = ramp,
                   .mean_mm = {},
                   .max_mm = {},
                   .force_err_mN = {},
                   .force_full_mN = {}};
  integrators::Trapezoid trapezoid(o.dt);
  model::State state = model::State::at_rest(reduced.size());
  trapezoid.reset(reduced, state);
  simulation::run(trapezoid, state, o.dt, o.steps, {[&](long k, const model::State& s, double) {
                    const auto step = static_cast<std::size_t>(k - 1);
                    const RoiError e = roi_error(setup.node_dofs, s.u, reference.u[step]);
                    curve.mean_mm.push_back(e.mean / mm);
                    curve.max_mm.push_back(e.max / mm);
                    if (!tools.empty()) {
                      const auto [error, largest] = force_error_mN(tools.forces(s.u, s.t), reference.forces[step]);
                      curve.force_err_mN.push_back(error);
                      curve.force_full_mN.push_back(largest);
                    }
                    if (record_fields && k % o.field_every == 0)
                      record.add(record.roi_series, format("fields/setup1/displacement_mm_%04ld", k), s,
                                 field_mm(m, tools, setup.condensation->expand(s.u, s.t), s.t));
                  }},
                  format("%s %s, ramp %.1f s", setup.name.c_str(), setup.label.c_str(), ramp));
  return curve;
}

void PaperExperiment::measure_accuracy() {
  const PaperOptions& o = o_;
  const std::vector<Setup>& setups = setups_;
  PaperResults& results = results_;
  record_.full_series = {.h5_name = "results.h5", .nodes = model_->mesh.num_nodes(), .tets = model_->mesh.num_tets()};
  record_.roi_series = record_.full_series;
  for (double ramp : o.ramps_s) {
    const Reference reference = run_reference(ramp);
    for (std::size_t si = 0; si < setups.size(); ++si) {
      const bool record_fields = si == 0 && ramp == o.ramps_s.front();  // setup1, the paper's reduction
      PaperCurve curve = run_setup(setups[si], ramp, reference, record_fields);
      if (curve.static_condensation) results.curves.push_back(curve);
      results.reduction_curves.push_back(std::move(curve));
    }
  }
  // Setup-major (setup1: ramps..., setup2: ramps...).
  auto by_setup = [](const PaperCurve& a, const PaperCurve& b) { return a.setup < b.setup; };
  std::stable_sort(results.curves.begin(), results.curves.end(), by_setup);
  std::stable_sort(results.reduction_curves.begin(), results.reduction_curves.end(), by_setup);
}

void PaperExperiment::measure_speed() {
  const PaperOptions& o = o_;
  const PaperModel& m = *model_;
  const std::vector<Setup>& setups = setups_;
  PaperResults& results = results_;
  std::vector<const model::SecondOrderSystem*> timed{&m.full.system};
  for (const auto& setup : setups) timed.push_back(&setup.condensation->system());
  const auto step_seconds = time_steps(timed, o.dt, o.timing_steps);
  results.timing.push_back({"full", m.mesh.num_nodes(), m.full.dofs->num_free(), simulation::median(step_seconds[0]),
                            simulation::percentile(step_seconds[0], 0.99), std::nullopt});
  for (std::size_t si = 0; si < setups.size(); ++si) {
    const auto& setup = setups[si];
    const auto& seconds = step_seconds[si + 1];
    if (setup.reduction.is_static_condensation())
      results.timing.push_back({setup.name, static_cast<Index>(setup.condensation->partition().roi_nodes.size()),
                                setup.condensation->system().size(), simulation::median(seconds),
                                simulation::percentile(seconds, 0.99), setup.setup_s});
    const auto& curve = *std::find_if(results.reduction_curves.begin(), results.reduction_curves.end(), [&](const PaperCurve& c) {
      return c.setup == setup.name && c.reduction == setup.label && c.ramp_s == o.ramps_s.front();
    });
    results.reductions.push_back(
        {.setup = setup.name,
         .reduction = setup.label,
         .static_condensation = setup.reduction.is_static_condensation(),
         .dofs = setup.condensation->system().size(),
         .extra_dofs = setup.condensation->num_modes(),
         .ramp_s = curve.ramp_s,
         .peak_max_mm = *std::max_element(curve.max_mm.begin(), curve.max_mm.end()),
         .steady_mean_mm = steady_mean(curve),
         .step_s_median = simulation::median(seconds),
         .setup_s = setup.setup_s,
         .peak_force_err_mN = curve.force_err_mN.empty()
                                  ? std::nullopt
                                  : std::optional(*std::max_element(curve.force_err_mN.begin(), curve.force_err_mN.end()))});
  }
}

void PaperExperiment::write_results() const {
  write_paper_tables(results_, o_.out);
  write_results_h5();
}

void PaperExperiment::write_results_h5() const {
  const PaperOptions& o = o_;
  const PaperModel& m = *model_;
  const std::vector<Setup>& setups = setups_;
  const PaperResults& results = results_;
  const FieldRecord& record = record_;
  AtomicFile file(o.out / "results.h5");
  {
    io::Hdf5Writer h5(file.temporary_path());
    const auto n = static_cast<hsize_t>(m.mesh.num_nodes());
    io::write_mesh(h5, m.mesh);
    for (const auto& setup : setups) {
      if (!setup.reduction.is_static_condensation()) continue;
      const auto& roi_nodes = setup.condensation->partition().roi_nodes;
      h5.write(setup.name + "/roi_nodes", roi_nodes, {roi_nodes.size()});
    }
    for (const auto& c : results.reduction_curves) {
      const std::string group = format("errors/%s/%s/ramp_%gs/", c.setup.c_str(), c.reduction.c_str(), c.ramp_s);
      h5.write(group + "mean_mm", c.mean_mm, {c.mean_mm.size()});
      h5.write(group + "max_mm", c.max_mm, {c.max_mm.size()});
      if (!c.force_err_mN.empty()) {
        h5.write(group + "force_err_mN", c.force_err_mN, {c.force_err_mN.size()});
        h5.write(group + "force_full_mN", c.force_full_mN, {c.force_full_mN.size()});
      }
    }
    std::vector<double> medians;
    std::string models;
    for (const auto& t : results.timing) {
      medians.push_back(t.step_s_median);
      models += (models.empty() ? "" : ", ") + t.model;
    }
    h5.write("timing/step_s_median", medians, {medians.size()});
    for (const auto& [name, data] : record.fields) h5.write(name, data, {n, 3});
    h5.attribute("experiment", "Hansen & Larsen 1998, Section 5: full model vs condensed ROI setups");
    h5.attribute("mesh", o.mesh.string());
    h5.attribute("material", o.material);
    h5.attribute("drive", o.drive == PaperDrive::spatulas ? "spatulas" : "forces");
    h5.attribute("force_per_wall_N", format("%.9g", results.force_N));
    h5.attribute("opening_mm", format("%g", o.opening_mm));
    h5.attribute("dt_s", format("%g", o.dt));
    h5.attribute("steps", std::to_string(o.steps));
    h5.attribute("timing_models", models);
    h5.attribute("fields", "full and setup1 (static part recovered) displacement, ramp 0.5 s, every " +
                               std::to_string(o.field_every) + " steps");
    h5.close();
  }
  file.commit();
  io::write_xdmf(o.out / "results.xdmf", record.full_series);
  if (!record.roi_series.fields.empty()) io::write_xdmf(o.out / "results_setup1.xdmf", record.roi_series);
}

void PaperExperiment::plot(const char* script, const std::vector<std::string>& pngs) const {
  if (!o_.plots || !io::run_plot_script(script, o_.out, log_)) return;
  std::string list;
  for (const auto& png : pngs) list += (list.empty() ? "" : ", ") + (o_.out / png).string();
  log_ << "\nplots: " << list << std::endl;
}

void PaperExperiment::measure_error_budget() {
  const PaperOptions& o = o_;
  const std::vector<Setup>& setups = setups_;
  const PaperResults& results = results_;
  BudgetInput in{.full = &model_->full,
                 .fixed_sets = {o.fixed_set},
                 .force_N = results.force_N,
                 .dt = o.dt,
                 .steps = o.steps,
                 .ramps_s = o.ramps_s,
                 .setups = {},
                 .reduction = {}};
  for (const auto& setup : setups) {
    if (!setup.reduction.is_static_condensation()) continue;
    in.setups.emplace_back(setup.name, setup.condensation->partition().roi_nodes);
    auto& curves = in.reduction.emplace_back();
    for (double ramp : o.ramps_s)
      for (const auto& c : results.curves)
        if (c.setup == setup.name && c.ramp_s == ramp) curves.push_back({c.mean_mm, c.max_mm});
  }
  results_.budget = experiments::measure_error_budget(in, o.budget, o.out, log_);
}

}  // namespace

PaperResults run_paper_experiment(const PaperOptions& o, std::ostream& log) { return PaperExperiment(o, log).run(); }

}  // namespace roifem::experiments
