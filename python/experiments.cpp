// SPDX-License-Identifier: GPL-3.0-or-later
// The studies of the CLI from Python: roifem.paper, roifem.compare and roifem.roi_size run the same
// code as `roifem paper`, `roifem compare` and `roifem roi-size` (writing the same files into
// `out`) and return their tables as NumPy structured arrays in a dict.
#include <pybind11/iostream.h>

#include <cmath>
#include <ostream>
#include <span>
#include <type_traits>
#include <variant>

#include "bindings.hpp"
#include "common/errors.hpp"
#include "common/interrupt.hpp"
#include "experiments/compare_experiment.hpp"
#include "experiments/compare_results.hpp"
#include "experiments/paper_experiment.hpp"
#include "experiments/paper_results.hpp"
#include "experiments/roi_size.hpp"
#include "io/result_table.hpp"
#include "scenario_handle.hpp"

namespace roifem::python {

namespace {

/// The log the studies print to: Python's sys.stdout (so notebooks and redirections see it), or nothing.
class Log {
 public:
  explicit Log(bool verbose) : buffer_(py::module_::import("sys").attr("stdout")), stream_(verbose ? &buffer_ : nullptr) {}
  ~Log() { stream_.flush(); }
  Log(const Log&) = delete;
  Log& operator=(const Log&) = delete;
  std::ostream& stream() { return stream_; }

 private:
  py::detail::pythonbuf buffer_;
  std::ostream stream_;
};

/// Runs `study` with Ctrl-C turned into a stop between two steps (roifem::Interrupted, which
/// reaches Python as KeyboardInterrupt), and Python's own handler back afterwards. The GIL is
/// released meanwhile: other Python threads run (the log takes it back for each line it prints).
template <class Study>
auto interruptible(Study&& study) {
  const InterruptGuard guard;
  auto result = [&] {
    const py::gil_scoped_release unlocked;
    return study();
  }();
  if (const int signal_number = InterruptGuard::signal_received())
    throw Interrupted(signal_number, "interrupted by signal " + std::to_string(signal_number));
  return result;
}

template <class Row, class F>
py::object column(const std::vector<Row>& rows, F&& field) {
  py::list out;
  for (const Row& r : rows) out.append(field(r));
  return out;
}

/// A result table (io/result_table.hpp) as a NumPy structured array, from the same column list
/// its CSV file is written from: a cell without a figure is NaN, and a flag is 1.0 / 0.0 (so that
/// a column's dtype does not depend on whether one of its cells is empty).
template <class Row>
py::object structured_table(std::span<const io::Column<Row>> columns, const std::vector<Row>& rows) {
  std::vector<std::string> names;
  std::vector<py::object> cols;
  for (const auto& c : columns) {
    names.emplace_back(c.name);
    py::list values;
    for (const Row& row : rows)
      values.append(std::visit(
          [](const auto& x) -> py::object {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, std::monostate>)
              return py::float_(std::nan(""));
            else if constexpr (std::is_same_v<T, bool>)
              return py::float_(x ? 1.0 : 0.0);
            else
              return py::cast(x);
          },
          c.value(row)));
    cols.push_back(values);
  }
  return structured_array(names, cols);
}

std::vector<condensation::Reduction> reductions_of(const std::vector<std::string>& labels) {
  std::vector<condensation::Reduction> out;
  for (const auto& label : labels) out.push_back(condensation::parse_reduction(label));
  return out;
}

/// The labels of `reductions` (their defaults in Python are the C++ options' own).
std::vector<std::string> labels_of(const std::vector<condensation::Reduction>& reductions) {
  std::vector<std::string> out;
  for (const auto& r : reductions) out.push_back(r.label());
  return out;
}

py::dict paper_results(const experiments::PaperResults& r) {
  py::dict d;
  d["force_N"] = r.force_N;
  d["opening_mm"] = r.opening_mm;
  const auto steps = experiments::paper_steps(r);
  d["errors"] = structured_table(experiments::error_columns(), steps);
  if (r.drive == experiments::PaperDrive::spatulas)
    d["force_errors"] = structured_table(experiments::force_error_columns(), steps);
  d["timing"] = structured_table(experiments::timing_columns(), r.timing);
  d["reductions"] = structured_table(experiments::reduction_columns(), r.reductions);
  d["interface_nodes"] = r.interface_nodes;
  return d;
}

py::dict compare_results(const experiments::CompareResults& r) {
  py::dict d;
  d["rows"] = structured_table(experiments::compare_columns(), r.rows);
  d["stability"] = structured_table(experiments::stability_columns(), r.stability);
  d["omega_max"] = r.omega_max;
  return d;
}

py::dict roi_size_results(const experiments::RoiSizeResults& r) {
  py::dict d;
  d["rows"] = structured_table(experiments::roi_size_columns(), r.rows);
  py::dict probes;
  for (const auto& row : r.rows)
    probes[row.reduction.c_str()] = structured_table(experiments::roi_size_run_columns(), experiments::runs_of(row));
  d["probes"] = probes;
  d["target_mm"] = std::vector<double>{r.target.x() / mm, r.target.y() / mm, r.target.z() / mm};
  d["free_nodes"] = r.free_nodes;
  d["full_step_s_median"] = r.full_step_s_median;
  d["scenario_roi"] = r.scenario_roi;
  d["scenario_roi_nodes"] = r.scenario_roi_nodes;
  d["scenario_peak_max_mm"] = r.scenario_peak_max_mm;
  return d;
}

}  // namespace

void bind_experiments(py::module_& m) {
  // Python's defaults are read from the C++ options, so the two never drift apart.
  const experiments::PaperOptions paper;
  const experiments::CompareOptions compare;
  const experiments::RoiSizeOptions roi_size;
  m.def(
      "paper",
      [](const std::filesystem::path& mesh, const std::filesystem::path& out, const std::string& material,
         const std::string& drive, double opening_mm, double dt, long steps, const std::vector<double>& ramps_s,
         const std::vector<Index>& setup_nodes, const std::array<double, 3>& target_mm, const std::string& fixed_set,
         const std::vector<std::string>& reductions, long timing_steps, long field_every, bool plots, bool error_budget,
         bool verbose) {
        experiments::PaperOptions o;
        o.mesh = mesh;
        o.out = out;
        o.material = material;
        if (drive != "forces" && drive != "spatulas")
          throw InputError("paper: drive '" + drive + "' is not one of: forces, spatulas");
        o.drive = drive == "forces" ? experiments::PaperDrive::forces : experiments::PaperDrive::spatulas;
        o.opening_mm = opening_mm;
        o.dt = dt;
        o.steps = steps;
        o.ramps_s = ramps_s;
        o.setup_nodes = setup_nodes;
        o.roi_target_mm = Vec3(target_mm[0], target_mm[1], target_mm[2]);
        o.fixed_set = fixed_set;
        o.reductions = reductions_of(reductions);
        o.timing_steps = timing_steps;
        o.field_every = field_every;
        o.plots = plots;
        o.error_budget = error_budget;
        Log log(verbose);
        return paper_results(interruptible([&] { return experiments::run_paper_experiment(o, log.stream()); }));
      },
      py::arg("mesh"), py::arg("out"), py::arg("material") = paper.material, py::arg("drive") = "forces",
      py::arg("opening_mm") = paper.opening_mm, py::arg("dt") = paper.dt, py::arg("steps") = paper.steps,
      py::arg("ramps_s") = paper.ramps_s, py::arg("setup_nodes") = paper.setup_nodes,
      py::arg("target_mm") = std::array<double, 3>{paper.roi_target_mm.x(), paper.roi_target_mm.y(), paper.roi_target_mm.z()},
      py::arg("fixed_set") = paper.fixed_set, py::arg("reductions") = labels_of(paper.reductions),
      py::arg("timing_steps") = paper.timing_steps, py::arg("field_every") = paper.field_every, py::arg("plots") = paper.plots,
      py::arg("error_budget") = paper.error_budget, py::arg("verbose") = true,
      "Hansen & Larsen's experiment, as `roifem paper` runs it (its files go to `out`). Returns a dict: force_N, "
      "opening_mm, errors (errors.csv's columns: per setup, reduction, ramp and step, mean_mm and max_mm), "
      "force_errors (driven by spatulas: force_errors.csv's), timing (Table 2: timing.csv's), reductions "
      "(reductions.csv's: one row per setup and reduction at the fastest ramp) and interface_nodes.");

  m.def(
      "compare",
      [](const py::object& scenario, const std::filesystem::path& out, const std::vector<std::string>& integrators, double t_end,
         int fixed_levels, const std::vector<double>& tolerances, long max_steps, double max_run_s, bool plots, bool verbose) {
        experiments::CompareOptions o;
        o.out = out;
        o.integrators = integrators;
        o.t_end = t_end;
        o.fixed_levels = fixed_levels;
        o.tolerances = tolerances;
        o.max_steps = max_steps;
        o.max_run_s = max_run_s;
        o.plots = plots;
        Log log(verbose);
        const ScenarioHandle sc = scenario_handle_of(scenario);
        return compare_results(interruptible([&] { return experiments::run_compare(sc.scenario, o, log.stream()); }));
      },
      py::arg("scenario"), py::arg("out"), py::arg("integrators") = compare.integrators, py::arg("t_end") = compare.t_end,
      py::arg("fixed_levels") = compare.fixed_levels, py::arg("tolerances") = compare.tolerances,
      py::arg("max_steps") = compare.max_steps, py::arg("max_run_s") = compare.max_run_s, py::arg("plots") = compare.plots,
      py::arg("verbose") = true,
      "Every integrator named (all when empty) on the scenario, as `roifem compare` runs it, against the exact modal "
      "solution. Returns a dict: rows (the columns of compare.csv: integrator, mode, dt_or_tol, theoretical_order, "
      "counters, wall_s, err_max_mm, err_rms_mm, stable (1.0, 0.0, NaN if stopped), energy_drift_rel, status; NaN "
      "figures for a run that did not finish stably), stability (the columns of stability.csv) and omega_max (rad/s).");

  m.def(
      "roi_size",
      [](const std::filesystem::path& scenario, double max_error_mm, const std::vector<std::string>& reductions,
         const std::string& integrator, Index start_nodes, double coarse, double resolution, long timing_steps,
         const std::optional<std::filesystem::path>& out, bool verbose) {
        experiments::RoiSizeOptions o;
        o.scenario = scenario;
        o.max_error_mm = max_error_mm;
        o.reductions = reductions_of(reductions);
        o.integrator = integrator;
        o.start_nodes = start_nodes;
        o.coarse = coarse;
        o.resolution = resolution;
        o.timing_steps = timing_steps;
        o.out = out.value_or(std::filesystem::path{});
        Log log(verbose);
        return roi_size_results(interruptible([&] { return experiments::run_roi_size(o, log.stream()); }));
      },
      py::arg("scenario"), py::arg("max_error_mm") = roi_size.max_error_mm,
      py::arg("reductions") = labels_of(roi_size.reductions), py::arg("integrator") = roi_size.integrator,
      py::arg("start_nodes") = roi_size.start_nodes, py::arg("coarse") = roi_size.coarse,
      py::arg("resolution") = roi_size.resolution, py::arg("timing_steps") = roi_size.timing_steps, py::arg("out") = py::none(),
      py::arg("verbose") = true,
      "The smallest ROI around the scenario's target from which every larger one keeps the error within "
      "max_error_mm, per reduction, as `roifem roi-size` finds it. Returns a dict: rows (roi_size.csv's columns), probes (per "
      "reduction: roi_size_runs.csv's rows, "
      "every size tried and its error), target_mm, free_nodes, full_step_s_median, and the scenario's own ROI.");
}

}  // namespace roifem::python
