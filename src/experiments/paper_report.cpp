// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/paper_report.hpp"
#include "common/format.hpp"

#include <algorithm>
#include <ostream>

#include "common/number_text.hpp"
#include "io/result_table.hpp"

namespace roifem::experiments {

namespace {

double peak(const std::vector<double>& values) { return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end()); }

void print_reductions(const PaperResults& r, std::ostream& log) {
  if (r.reductions.empty()) return;
  log << format("\nBeyond the paper: the static part's inertia (ramp %.1f s; step cost of the trapezoidal rule, median)\n",
                r.reductions.front().ramp_s);
  const bool spatulas = r.drive == PaperDrive::spatulas;
  log << format("  %-7s %-18s %5s %6s %15s %17s %11s %9s %9s%s\n", "setup", "reduction", "dofs", "extra", "peak max (mm)",
                "steady mean (mm)", "step (ms)", "vs static", "peak /", spatulas ? "   force err (mN)" : "");
  for (const auto& row : r.reductions) {
    const auto& plain = *std::find_if(r.reductions.begin(), r.reductions.end(),
                                      [&](const ReductionRow& x) { return x.setup == row.setup && x.static_condensation; });
    log << format("  %-7s %-18s %5lld %6lld %15.4f %17.5f %11.4f %8.2fx %8.1fx", row.setup.c_str(), row.reduction.c_str(),
                  static_cast<long long>(row.dofs), static_cast<long long>(row.extra_dofs), row.peak_max_mm, row.steady_mean_mm,
                  row.step_s_median * 1e3, row.step_s_median / plain.step_s_median, plain.peak_max_mm / row.peak_max_mm);
    log << (spatulas ? format(" %16.4f\n", row.peak_force_err_mN.value_or(0.0)) : std::string("\n"));
  }
  log << "  (vs static: step cost relative to plain condensation; peak /: how many times lower the peak is"
      << (spatulas ? ";\n   force err: the peak of the spatulas' force error)\n" : ")\n");
}

void print_findings(const PaperResults& r, std::ostream& log) {
  log << "\nFindings (Hansen & Larsen 1998, Section 5), checked on this run"
      << (r.drive == PaperDrive::spatulas ? ", driven by spatulas:\n" : ":\n");
  std::vector<double> step_s;
  for (const auto& t : r.timing) step_s.push_back(t.step_s_median);
  // The linear runs take every step or throw: each curve is complete.
  long steps = 0;
  for (const auto& c : r.curves) steps = std::max(steps, static_cast<long>(c.max_mm.size()));
  print_findings(r.curves, r.ramps_s.size(), steps, step_s, log);
  // The model is linear: every error scales with the force. Say at which scale this run is.
  if (!r.curves.empty() && r.opening_mm > 0) {
    const double scale = paper_peak_max_error_mm / peak(r.curves.front().max_mm);
    log << format(
        "  Scale: the model is linear, so the errors scale with the load. Here %s peaks at %.3g mm at the %.1f s ramp, the "
        "paper's "
        "Fig. 6 at about %.0f mm; --opening-mm %.4g gives the paper's scale.\n",
        r.curves.front().setup.c_str(), peak(r.curves.front().max_mm), r.curves.front().ramp_s, paper_peak_max_error_mm,
        r.opening_mm * scale);
  }
}

/// Beyond the paper, driven by spatulas: the error of the force each spatula feels, per setup and
/// ramp (the paper's reduction), against the full model's force.
void print_tool_forces(const PaperResults& r, std::ostream& log) {
  if (r.drive != PaperDrive::spatulas) return;
  log << "\nThe force the surgeon feels (beyond the paper): each spatula's force on the tissue, condensed vs full\n";
  log << format("  %-8s %6s %16s %16s %9s %18s\n", "setup", "ramp", "full peak (mN)", "peak err (mN)", "% of peak",
                "steady err (mN)");
  for (const auto& c : r.curves)
    log << format("  %-8s %5.1fs %16.3f %16.4f %8.3f%% %18.3e\n", c.setup.c_str(), c.ramp_s, peak(c.force_full_mN),
                  peak(c.force_err_mN), 100 * peak(c.force_err_mN) / peak(c.force_full_mN), steady_force_err(c));
  log << "  (per step the larger of the two spatulas' |F_condensed - F_full|; % of the full model's peak force;\n"
         "   steady: the mean over steps > 100, as the paper's steady error: the damped transient still rings there,\n"
         "   and static condensation is exact only at rest)\n";
}

/// Hansen & Larsen's Table 2 figure for a model of ours, or 0 where the paper has none.
double paper_step_s(const std::string& model) {
  if (model == "full") return paper_full_step_s;
  if (model == "setup1") return paper_setup1_step_s;
  if (model == "setup2") return paper_setup2_step_s;
  return 0.0;
}

void print_table2(const PaperResults& r, std::ostream& log) {
  log << "\nTable 2: time per step (trapezoidal rule, dt = 0.05 s; real time at 20 Hz needs < 50 ms)\n";
  log << format("  %-8s %6s %6s %12s %14s %11s %14s %10s\n", "model", "nodes", "dofs", "1998 (s)", "roifem (ms)", "p99 (ms)",
                "frame rate", "vs full");
  for (std::size_t k = 0; k < r.timing.size(); ++k) {
    const auto& t = r.timing[k];
    log << format("  %-8s %6lld %6lld %12.3f %14.4f %11.4f %11.0f Hz %9.2fx\n", t.model.c_str(), static_cast<long long>(t.nodes),
                  static_cast<long long>(t.dofs), paper_step_s(t.model), t.step_s_median * 1e3, t.step_s_p99 * 1e3,
                  1.0 / t.step_s_median, r.timing[0].step_s_median / t.step_s_median);
  }
  log << "  (1998: the paper's figures on its hardware; roifem: medians of per-step wall time on this machine)\n";
}

}  // namespace

namespace {

/// Folds one check into a finding: a check on something not measured makes the finding not
/// measured, whatever else holds; otherwise one failure fails it.
void fold(Finding& finding, bool measured, bool holds) {
  if (finding == Finding::not_measured) return;
  if (!measured)
    finding = Finding::not_measured;
  else if (!holds)
    finding = Finding::fails;
}

}  // namespace

bool PaperFindings::all_measured() const {
  for (const Finding f : {steady_below_0_2_mm, faster_ramp_peaks_higher, smaller_roi_peaks_higher, condensed_step_faster})
    if (f == Finding::not_measured) return false;
  return true;
}

PaperFindings check_findings(const std::vector<PaperCurve>& curves, std::size_t n_ramps, long steps,
                             const std::vector<double>& step_s) {
  PaperFindings f;
  auto complete = [steps](const PaperCurve& c) { return static_cast<long>(c.max_mm.size()) >= steps && !c.max_mm.empty(); };
  for (const auto& c : curves) fold(f.steady_below_0_2_mm, complete(c) && c.mean_mm.size() > 100, steady_mean(c) < 0.2);
  const std::size_t n_setups = n_ramps ? curves.size() / n_ramps : 0;
  // A comparison with nothing to compare (one ramp, one setup, no condensed model) is not measured.
  if (curves.empty()) f.steady_below_0_2_mm = Finding::not_measured;
  if (n_ramps < 2 || n_setups == 0) f.faster_ramp_peaks_higher = Finding::not_measured;
  if (n_setups < 2) f.smaller_roi_peaks_higher = Finding::not_measured;
  if (step_s.size() < 2) f.condensed_step_faster = Finding::not_measured;
  for (std::size_t s = 0; s < n_setups; ++s)
    for (std::size_t k = 0; k + 1 < n_ramps; ++k) {
      const PaperCurve &faster = curves[s * n_ramps + k], &slower = curves[s * n_ramps + k + 1];
      fold(f.faster_ramp_peaks_higher, complete(faster) && complete(slower), peak(faster.max_mm) > peak(slower.max_mm));
    }
  for (std::size_t k = 0; k < n_ramps && n_setups > 1; ++k)
    fold(f.smaller_roi_peaks_higher, complete(curves[k]) && complete(curves[n_ramps + k]),
         peak(curves[n_ramps + k].max_mm) > peak(curves[k].max_mm));
  for (std::size_t k = 1; k < step_s.size(); ++k)
    fold(f.condensed_step_faster, step_s[0] > 0 && step_s[k] > 0, step_s[k] < step_s[0]);
  return f;
}

void print_findings(const std::vector<PaperCurve>& curves, std::size_t n_ramps, long steps, const std::vector<double>& step_s,
                    std::ostream& log) {
  for (const auto& c : curves) {
    const std::string steady = c.mean_mm.size() > 100 ? format("%.4f mm", steady_mean(c)) : std::string("- (not measured)");
    const std::string stopped = static_cast<long>(c.max_mm.size()) < steps
                                    ? format(" (stopped after %zu of %ld steps)", c.max_mm.size(), steps)
                                    : std::string();
    log << format("  %-8s ramp %.1f s: peak max error %6.3f mm, peak mean error %6.3f mm, steady mean error (steps > 100) %s%s\n",
                  c.setup.c_str(), c.ramp_s, peak(c.max_mm), peak(c.mean_mm), steady.c_str(), stopped.c_str());
  }
  const PaperFindings f = check_findings(curves, n_ramps, steps, step_s);
  auto mark = [](Finding finding) { return finding == Finding::holds ? "yes" : finding == Finding::fails ? "NO" : "--"; };
  log << format("  [%s] steady-state mean error below 0.2 mm for every ramp and setup\n", mark(f.steady_below_0_2_mm));
  log << format("  [%s] the faster the ramp, the higher the max-error peak (0.5 s highest, 2 s lowest)\n",
                mark(f.faster_ramp_peaks_higher));
  log << format("  [%s] setup 2 (smaller ROI) peaks above setup 1\n", mark(f.smaller_roi_peaks_higher));
  log << format("  [%s] the condensed models step faster than the full model\n", mark(f.condensed_step_faster));
}

void print_paper_report(const PaperResults& r, std::ostream& log) {
  print_findings(r, log);
  print_tool_forces(r, log);
  print_table2(r, log);
  print_reductions(r, log);
}

void write_paper_tables(const PaperResults& results, const std::filesystem::path& out) {
  const auto steps = paper_steps(results);
  io::write_csv(out / "errors.csv", error_columns(), steps);
  io::write_csv(out / "reductions.csv", reduction_columns(), results.reductions);
  io::write_csv(out / "timing.csv", timing_columns(), results.timing);
  if (results.drive == PaperDrive::spatulas) io::write_csv(out / "force_errors.csv", force_error_columns(), steps);
}

}  // namespace roifem::experiments
