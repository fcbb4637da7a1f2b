// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/tissue_fit.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <ostream>
#include <set>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/number_text.hpp"
#include "experiments/homogeneous_response.hpp"
#include "io/csv.hpp"
#include "io/plots.hpp"

namespace roifem::experiments {

namespace {

constexpr double kPa = 1e3;

int parameter_count(const std::string& law) { return law == "ogden" ? 2 : 1; }

std::string law_title(const std::string& law) { return law == "ogden" ? "one-term Ogden" : "neo-Hookean"; }

/// The parameters as the solver sees them: log(mu / 1 kPa), and Ogden's alpha.
LawFit from_parameters(const std::string& region, const std::string& law, const double* x, double bulk_ratio) {
  LawFit fit{.region = region, .law = law};
  fit.mu_Pa = kPa * std::exp(x[0]);
  fit.alpha = law == "ogden" ? x[1] : 2.0;
  fit.lambda_Pa = (bulk_ratio - 2.0 / 3.0) * fit.mu_Pa;
  return fit;
}

struct Problem {
  const std::vector<const TissueCurve*>* curves;
  std::string region, law;
  double bulk_ratio;
  /// 1 / sqrt(the mode's point count): the sum of squares is the sum of the modes' mean squares,
  /// so that each mode counts alike however many points it has (Budday's shear curves have twice
  /// the points of the others).
  std::map<TissueMode, double> weight;
};

/// Residuals (model - data) in kPa; GSL_EDOM where the parameters leave the law's domain.
int residuals(const gsl_vector* x, void* data, gsl_vector* f) {
  const auto* problem = static_cast<const Problem*>(data);
  try {
    const LawFit fit = from_parameters(problem->region, problem->law, x->data, problem->bulk_ratio);
    if (!std::isfinite(fit.mu_Pa) || fit.mu_Pa <= 0 || fit.alpha == 0 || !std::isfinite(fit.alpha)) return GSL_EDOM;
    const fem::Material material = fitted_material(fit, problem->bulk_ratio);
    std::size_t i = 0;
    for (const TissueCurve* curve : *problem->curves) {
      const std::vector<double> model = model_stress(material, *curve);
      const double weight = problem->weight.at(curve->mode);
      for (std::size_t k = 0; k < model.size(); ++k, ++i) gsl_vector_set(f, i, weight * (model[k] - curve->stress_Pa[k]) / kPa);
    }
    for (i = 0; i < f->size; ++i)
      if (!std::isfinite(gsl_vector_get(f, i))) return GSL_EDOM;
    return GSL_SUCCESS;
  } catch (const std::exception&) {  // no exception may cross GSL's C frames
    return GSL_EDOM;
  }
}

struct WorkspaceFree {
  void operator()(gsl_multifit_nlinear_workspace* w) const { gsl_multifit_nlinear_free(w); }
};

struct Attempt {
  std::vector<double> x;
  double cost = std::numeric_limits<double>::infinity();
  int iterations = 0;
  int status = GSL_FAILURE;
};

Attempt solve_from(const Problem& problem, std::size_t n, std::vector<double> x0, int max_iterations) {
  const std::size_t p = x0.size();
  gsl_multifit_nlinear_parameters parameters = gsl_multifit_nlinear_default_parameters();
  const std::unique_ptr<gsl_multifit_nlinear_workspace, WorkspaceFree> w(
      gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &parameters, n, p));
  gsl_multifit_nlinear_fdf fdf{};
  fdf.f = &residuals;
  fdf.n = n;
  fdf.p = p;
  fdf.params = const_cast<Problem*>(&problem);
  gsl_vector_view start = gsl_vector_view_array(x0.data(), p);
  Attempt attempt;
  if (gsl_multifit_nlinear_init(&start.vector, &fdf, w.get()) != GSL_SUCCESS) return attempt;
  int info = 0;
  attempt.status =
      gsl_multifit_nlinear_driver(static_cast<std::size_t>(max_iterations), 1e-10, 1e-10, 0.0, nullptr, nullptr, &info, w.get());
  const gsl_vector* x = gsl_multifit_nlinear_position(w.get());
  const gsl_vector* f = gsl_multifit_nlinear_residual(w.get());
  attempt.x.assign(x->data, x->data + p);
  double cost = 0;
  for (std::size_t i = 0; i < n; ++i) cost += gsl_vector_get(f, i) * gsl_vector_get(f, i);
  attempt.cost = std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
  attempt.iterations = static_cast<int>(gsl_multifit_nlinear_niter(w.get()));
  return attempt;
}

std::string file_part(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s;
}

void write_material_table(const std::filesystem::path& path, const LawFit& fit, const TissueFitOptions& options) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temporary_path());
    out << "# roifem fit: " << law_title(fit.law) << " for region '" << fit.region << "' of " << options.data.string()
        << ", kappa = " << number_text(options.bulk_ratio) << " mu (nearly incompressible)\n";
    out << "# RMSE (kPa):";
    for (const auto& [mode, rmse] : fit.rmse_Pa) out << " " << mode_name(mode) << " " << format("%.4f", rmse / kPa);
    out << (fit.converged ? "" : "  (the fit did not converge: " + fit.stop_reason + ")") << "\n";
    out << "# Paste in place of a scenario's [material] table (density and damping: the brain preset's).\n";
    out << "[material]\npreset = \"brain\"\nmodel = \"" << fit.law << "\"\n";
    out << "mu_Pa = " << format("%.10g", fit.mu_Pa) << "\nlambda_Pa = " << format("%.10g", fit.lambda_Pa) << "\n";
    if (fit.law == "ogden") out << "ogden_alpha = [" << format("%.10g", fit.alpha) << "]\n";
    out.flush();
    if (!out) throw InputError(path.string() + ": could not be written");
  }
  file.commit();
}

}  // namespace

fem::Material fitted_material(const LawFit& fit, double bulk_ratio) {
  fem::Material material = fem::material_preset("brain");
  material.mu = fit.mu_Pa;
  material.lambda = (bulk_ratio - 2.0 / 3.0) * fit.mu_Pa;
  if (fit.law == "ogden") {
    material.model = fem::MaterialModel::ogden;
    material.ogden = {{fit.mu_Pa, fit.alpha}};
  } else {
    material.model = fem::MaterialModel::neo_hookean;
    material.ogden.clear();
  }
  return material;
}

std::vector<double> model_stress(const fem::Material& material, const TissueCurve& curve) {
  const fem::HyperelasticLaw law = fem::hyperelastic_law(material);
  std::vector<double> stress;
  stress.reserve(curve.deformation.size());
  for (const double x : curve.deformation)
    stress.push_back(curve.mode == TissueMode::shear ? simple_shear_stress(law, x) : uniaxial_nominal_stress(law, x));
  return stress;
}

LawFit fit_region(const std::vector<TissueCurve>& curves, const std::string& region, const std::string& law,
                  const TissueFitOptions& options) {
  if (law != "ogden" && law != "neo-hookean")
    throw InputError("--law " + law + ": roifem fit fits 'ogden' (one term: mu, alpha) or 'neo-hookean' (mu)");
  std::vector<const TissueCurve*> mine;
  std::size_t n = 0;
  for (const auto& curve : curves)
    if (curve.region == region) {
      mine.push_back(&curve);
      n += curve.deformation.size();
    }
  const int p = parameter_count(law);
  if (n < static_cast<std::size_t>(p) + 1)
    throw InputError(options.data.string() + ": region '" + region + "' has " + std::to_string(n) + " points; the " +
                     law_title(law) + " fit has " + std::to_string(p) + " parameters and needs at least " +
                     std::to_string(p + 1));
  Problem problem{&mine, region, law, options.bulk_ratio, {}};
  std::map<TissueMode, std::size_t> mode_points;
  for (const TissueCurve* curve : mine) mode_points[curve->mode] += curve->deformation.size();
  for (const auto& [mode, count] : mode_points) problem.weight[mode] = 1 / std::sqrt(static_cast<double>(count));
  // Starts: mu from the steepest data slope's order (1 kPa), alpha on both sides of zero; brain
  // tissue's lies near -20 (Budday et al. 2017), rubber's near 2 to 8.
  std::vector<std::vector<double>> starts;
  if (law == "ogden")
    for (double alpha : {-25.0, -10.0, -3.0, 3.0, 10.0}) starts.push_back({0.0, alpha});
  else
    starts.push_back({0.0});
  Attempt best;
  for (const auto& start : starts) {
    Attempt attempt = solve_from(problem, n, start, options.max_iterations);
    if (attempt.cost < best.cost) best = std::move(attempt);
  }
  if (best.x.empty())
    throw SolverError("roifem fit: the " + law_title(law) + " fit of region '" + region + "' found no point in the law's domain");
  LawFit fit = from_parameters(region, law, best.x.data(), options.bulk_ratio);
  fit.iterations = best.iterations;
  fit.converged = best.status == GSL_SUCCESS;
  fit.stop_reason = fit.converged ? "" : gsl_strerror(best.status);
  const fem::Material material = fitted_material(fit, options.bulk_ratio);
  double all = 0;
  for (const TissueCurve* curve : mine) {
    const std::vector<double> model = model_stress(material, *curve);
    double sum = 0;
    for (std::size_t k = 0; k < model.size(); ++k) sum += std::pow(model[k] - curve->stress_Pa[k], 2);
    const auto [it, fresh] = fit.rmse_Pa.emplace(curve->mode, sum);
    if (!fresh) it->second += sum;
    all += sum;
  }
  for (auto& [mode, sum] : fit.rmse_Pa) {
    std::size_t count = 0;
    for (const TissueCurve* curve : mine)
      if (curve->mode == mode) count += curve->deformation.size();
    sum = std::sqrt(sum / static_cast<double>(count));
  }
  fit.points = static_cast<int>(n);
  fit.rmse_all_Pa = std::sqrt(all / static_cast<double>(n));
  return fit;
}

void run_tissue_fit(const TissueFitOptions& options, std::ostream& out) {
  if (!(options.bulk_ratio > 1) || !std::isfinite(options.bulk_ratio))
    throw InputError("--bulk-ratio " + number_text(options.bulk_ratio) +
                     ": kappa / mu must be above 1 (a Poisson's ratio above 0.125)");
  if (options.laws.empty()) throw InputError("--law: name at least one law (ogden, neo-hookean)");
  for (const auto& law : options.laws)
    if (law != "ogden" && law != "neo-hookean")
      throw InputError("--law " + law + ": roifem fit fits 'ogden' (one term: mu, alpha) or 'neo-hookean' (mu)");
  const std::vector<TissueCurve> curves = read_tissue_curves(options.data);
  check_output_directory(options.out);
  std::vector<std::string> regions;
  std::size_t points = 0;
  std::set<TissueMode> modes;
  for (const auto& curve : curves) {
    if (std::find(regions.begin(), regions.end(), curve.region) == regions.end()) regions.push_back(curve.region);
    points += curve.deformation.size();
    modes.insert(curve.mode);
  }
  out << "roifem fit: " << options.data.string() << " (" << regions.size() << " regions, " << points
      << " points), kappa = " << number_text(options.bulk_ratio)
      << " mu, lateral faces free in tension and compression, simple shear exact\n";
  out << format("%-18s %-12s %10s %9s   RMSE (kPa): %8s %12s %8s %8s\n", "region", "law", "mu (kPa)", "alpha", "tension",
                "compression", "shear", "all");
  std::vector<LawFit> fits;
  for (const auto& region : regions)
    for (const auto& law : options.laws) {
      fits.push_back(fit_region(curves, region, law, options));
      const LawFit& f = fits.back();
      auto rmse = [&](TissueMode mode) {
        const auto it = f.rmse_Pa.find(mode);
        return it == f.rmse_Pa.end() ? std::string("-") : format("%.4f", it->second / kPa);
      };
      out << format("%-18s %-12s %10.4f %9s   %20s %12s %8s %8.4f%s\n", f.region.c_str(), f.law.c_str(), f.mu_Pa / kPa,
                    f.law == "ogden" ? format("%.3f", f.alpha).c_str() : "-", rmse(TissueMode::tension).c_str(),
                    rmse(TissueMode::compression).c_str(), rmse(TissueMode::shear).c_str(), f.rmse_all_Pa / kPa,
                    f.converged ? "" : ("  NOT CONVERGED: " + f.stop_reason).c_str());
    }

  io::CsvWriter table(options.out / "fit.csv",
                      "region,law,mu_Pa,alpha,lambda_Pa,bulk_ratio,rmse_tension_kPa,rmse_compression_kPa,rmse_shear_kPa,"
                      "rmse_kPa,points,iterations,converged");
  for (const auto& f : fits) {
    auto rmse = [&](TissueMode mode) {
      const auto it = f.rmse_Pa.find(mode);
      return it == f.rmse_Pa.end() ? std::string() : format("%.8g", it->second / kPa);
    };
    table.row(f.region + "," + f.law + "," +
              format("%.10g,%.10g,%.10g,%.10g,", f.mu_Pa, f.alpha, f.lambda_Pa, options.bulk_ratio) + rmse(TissueMode::tension) +
              "," + rmse(TissueMode::compression) + "," + rmse(TissueMode::shear) + "," +
              format("%.8g,%d,%d,", f.rmse_all_Pa / kPa, f.points, f.iterations) + (f.converged ? "yes" : "no"));
  }
  table.close();
  io::CsvWriter data(options.out / "fit_data.csv", "region,mode,deformation,nominal_stress_kPa");
  for (const auto& curve : curves)
    for (std::size_t k = 0; k < curve.deformation.size(); ++k)
      data.row(curve.region + "," + mode_name(curve.mode) + "," +
               format("%.10g,%.10g", curve.deformation[k], curve.stress_Pa[k] / kPa));
  data.close();
  // Each law's curve over each mode's measured range, 41 points.
  io::CsvWriter model(options.out / "fit_curves.csv", "region,law,mode,deformation,nominal_stress_kPa");
  for (const auto& f : fits) {
    const fem::Material material = fitted_material(f, options.bulk_ratio);
    for (const auto& curve : curves) {
      if (curve.region != f.region) continue;
      const auto [lo, hi] = std::minmax_element(curve.deformation.begin(), curve.deformation.end());
      TissueCurve dense{curve.region, curve.mode, {}, {}};
      for (int k = 0; k <= 40; ++k) dense.deformation.push_back(*lo + (*hi - *lo) * k / 40.0);
      const std::vector<double> stress = model_stress(material, dense);
      for (std::size_t k = 0; k < stress.size(); ++k)
        model.row(f.region + "," + f.law + "," + mode_name(curve.mode) + "," +
                  format("%.10g,%.10g", dense.deformation[k], stress[k] / kPa));
    }
  }
  model.close();
  std::vector<std::string> written{"fit.csv", "fit_data.csv", "fit_curves.csv"};
  for (const auto& f : fits) {
    const std::string name = "material-" + file_part(f.region) + "-" + f.law + ".toml";
    write_material_table(options.out / name, f, options);
    written.push_back(name);
  }
  if (io::run_plot_script("plot_fit.py", options.out, out)) written.emplace_back("fit-REGION.png (one per region)");
  out << "written in " << options.out.string() << ":";
  for (const auto& name : written) out << " " << name;
  out << "\n";
  for (const auto& f : fits)
    if (!f.converged)
      throw SolverError("roifem fit: the " + law_title(f.law) + " fit of region '" + f.region + "' did not converge in " +
                        std::to_string(options.max_iterations) + " iterations per start (" + f.stop_reason +
                        "); its best parameters are kept in " + (options.out / "fit.csv").string() +
                        " and marked converged = no");
}

}  // namespace roifem::experiments
