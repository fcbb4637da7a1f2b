// SPDX-License-Identifier: GPL-3.0-or-later
// The convergence study's table and CSV files (experiments/convergence_study.hpp).
#include <ostream>
#include <string>

#include "common/format.hpp"
#include "experiments/convergence_study.hpp"
#include "io/csv.hpp"

namespace roifem::experiments {

namespace {

/// Why a quantity's meshes are not (shown to be) in the asymptotic range, or "" when they are.
std::string why_not_asymptotic(const QuantityConvergence& q, std::size_t meshes) {
  if (q.asymptotic) return "";
  if (meshes < 3) return "two meshes show no order";
  if (q.observed_order) return format("observed order %.2f, the element's %g", *q.observed_order, formal_order);
  const std::size_t n = q.values.size();
  const double d12 = q.values[n - 3] - q.values[n - 2], d23 = q.values[n - 2] - q.values[n - 1];
  if ((d12 > 0) != (d23 > 0) || d12 == 0 || d23 == 0) return "the values are not monotone";
  return format("no order within [0.3, 4], the element's %g", formal_order);
}

/// A word on each quantity whose extrapolation is a guess, not an estimate.
void print_asymptotic_range(const ConvergenceResults& r, std::ostream& log) {
  std::string list;
  for (const auto& q : r.quantities)
    if (const std::string why = why_not_asymptotic(q, r.meshes.size()); !why.empty())
      list += (list.empty() ? "" : "; ") + q.name + " (" + why + ")";
  if (list.empty()) return;
  log << "warning: not in the asymptotic range: " << list
      << ". Their extrapolated values and errors are distances to a guess, not error estimates: finer or more meshes "
         "(--nodes), or --adapt.\n";
}

}  // namespace

void print_convergence_table(const ConvergenceResults& r, std::ostream& log) {
  log << format("\nConvergence (element %s, material '%s'); extrapolated by Richardson from the finest meshes\n",
                r.element.c_str(), r.material.c_str());
  log << format("%-13s %-4s", "quantity", "unit");
  for (const auto& m : r.meshes) log << format(" %12lld", static_cast<long long>(m.nodes));
  log << format(" %12s %7s\n", "extrapolated", "order");
  for (const auto& q : r.quantities) {
    log << format("%-13s %-4s", q.name.c_str(), q.unit.c_str());
    for (double v : q.values) log << format(" %12.5g", v);
    const std::string order = q.observed_order ? format("%.2f", *q.observed_order) : format("(%.3g)", q.order_used);
    log << format(" %12.5g %7s\n", q.extrapolated, order.c_str());
    log << format("%-13s %-4s", "  error", "%");
    for (double e : q.errors) log << format(" %12.3g", 100 * e / std::abs(q.extrapolated));
    log << "\n";
  }
  log << "order: observed from the three finest meshes; in brackets, the order used where none was observed: the\n"
         "formal order 2 where the meshes are not yet in the asymptotic range, and for the dynamic peak the probe's, with\n"
         "which its history is extrapolated step by step (its error: the largest distance over the run from that history).\n";
  print_asymptotic_range(r, log);
  const auto& opening = r.quantities.front();
  log << format(
      "The %lld-node model's spatial error on the opening: %.3f mm of %.3f mm (%.1f%%); at %lld nodes %.3f mm (%.1f%%)%s\n",
      static_cast<long long>(r.meshes.front().nodes), opening.errors.front(), opening.extrapolated,
      100 * opening.errors.front() / std::abs(opening.extrapolated), static_cast<long long>(r.meshes.back().nodes),
      opening.errors.back(), 100 * opening.errors.back() / std::abs(opening.extrapolated),
      opening.asymptotic ? "" : "; not an error estimate: these meshes are not shown to be in the asymptotic range (above)");
}

void write_convergence_csv(const ConvergenceResults& r, const std::filesystem::path& out) {
  io::CsvWriter table(out / "convergence.csv",
                      "quantity,unit,nodes,dofs,h_mm,value,error,rel_error_pct,order,observed,extrapolated");
  for (const auto& q : r.quantities)
    for (std::size_t i = 0; i < q.values.size(); ++i) {
      const auto& m = r.meshes[i];
      table.row(format("%s,%s,%lld,%lld,%.6g,%.10g,%.6g,%.6g,%.4g,%d,%.10g", q.name.c_str(), q.unit.c_str(),
                       static_cast<long long>(m.nodes), static_cast<long long>(m.dofs), m.h_mm, q.values[i], q.errors[i],
                       100 * q.errors[i] / std::abs(q.extrapolated), q.order_used, q.observed_order ? 1 : 0, q.extrapolated));
    }
  table.close();
  if (r.extrapolated_history_mm.empty()) return;
  std::string header = "t_s";
  for (const auto& m : r.meshes) header += format(",n%lld_mm", static_cast<long long>(m.nodes));
  io::CsvWriter history(out / "probe_history.csv", header + ",extrapolated_mm");
  for (std::size_t k = 0; k < r.extrapolated_history_mm.size(); ++k) {
    std::string line = format("%.6g", r.dt * static_cast<double>(k + 1));
    for (const auto& m : r.meshes) line += format(",%.10g", m.probe_history_mm[k]);
    history.row(line + format(",%.10g", r.extrapolated_history_mm[k]));
  }
  history.close();
}

}  // namespace roifem::experiments
