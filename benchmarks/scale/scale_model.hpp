// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// One measured model of a generated brain, built the way `roifem paper` builds its models (paper
/// material, base fixed, the opening's walls pulled apart over 0.5 s, trapezoidal rule at
/// dt = 0.05 s): the full dynamic model, or a condensed one whose ROI is the `roi_nodes` nodes
/// nearest the surgical target (0, 0, 40) mm; or the full model with the neo-Hookean law (same
/// lambda, mu), stepped by Newton, every step from rest timed.
///
/// A step is everything a simulator needs each tick: the new load, the step, and the
/// displacement out (copied to a buffer the renderer or haptic device would read).
#include <filesystem>
#include <string>
#include <vector>

#include "common/types.hpp"

namespace roifem::bench {

struct ModelSpec {
  std::string label;                 ///< "full", "full-cg", "roi-300", "roi-3%", ...
  Index roi_nodes = 0;               ///< 0: the full model
  bool conjugate_gradients = false;  ///< the full model by trapezoid-cg (no factor) instead of CHOLMOD
  long check_steps = 0;              ///< trapezoid-cg: steps compared against the direct solve (when its factor fits)
  bool neo_hookean = false;          ///< the full model with the neo-Hookean law: --steps steps from rest, all timed
  double load_scale = 1;             ///< the wall forces' factor (the neo-Hookean model)
};

struct TimingOptions {
  long max_steps = 200;       ///< timed steps at most
  double step_budget_s = 15;  ///< fewer steps when a model steps slowly (at least 10)
  long warmup_steps = 3;
};

struct ScaleMeasurement {
  long nodes = 0, dofs = 0, roi_nodes = 0, system_dofs = 0, interface_dofs = 0;
  double read_s = 0;              ///< mesh file read and checked
  double assembly_s = 0;          ///< dof map, K, M, C and loads
  double factorization_s = 0;     ///< condensed: ordering + factor of K over s and I; full: K_eff's; neo-Hookean: Newton's
  double condensation_s = 0;      ///< S read off the factor, loads reduced, reduced system assembled
  double integrator_setup_s = 0;  ///< condensed: the factor of the condensed K_eff
  double step_median_s = 0, step_p99_s = 0;
  long steps_timed = 0;
  double peak_rss_mb = 0;
  double cg_iterations_per_step = 0;  ///< trapezoid-cg
  double deviation_vs_direct = -1;    ///< trapezoid-cg: max_k |u_cg - u| / max_k |u| over check_steps; -1: not checked
  std::string check_note;             ///< why the check did not run
  double newton_per_step = 0;         ///< neo-Hookean: Newton iterations per step
  double all_steps_s = 0;             ///< neo-Hookean: every step from rest, in all
  double peak_displacement_mm = 0;    ///< neo-Hookean: max over the steps of max_i |u_i|
  long retried_steps = 0;             ///< neo-Hookean: steps solved again from u_n (line search, LU if indefinite)
  double setup_s() const { return assembly_s + factorization_s + condensation_s + integrator_setup_s; }

  std::string serialize() const;
  static ScaleMeasurement parse(const std::string& text);
};

ScaleMeasurement measure_model(const std::filesystem::path& mesh_file, const ModelSpec& spec, const TimingOptions& timing);

/// The free nodes of a generated brain (the base fixed): the largest ROI there is.
long free_nodes(const std::filesystem::path& mesh_file);

}  // namespace roifem::bench
