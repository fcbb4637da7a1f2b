// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/material_model.hpp"

#include <array>
#include <string>
#include <vector>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"

namespace roifem::fem {

namespace {
constexpr std::string_view hyperelastic_elements =
    "tet4, tet10; nodal-pressure in the full model (not the hybrid ROI, nor energy-momentum)";
constexpr std::string_view elastic_keys = "lambda_Pa and mu_Pa, or young_Pa and poisson (mu > 0, nu in (-1, 0.5))";
constexpr std::array<MaterialModelInfo, 3> material_models{{
    {MaterialModel::linear, "linear", "small-strain isotropic elasticity (the paper's): a constant K", elastic_keys,
     "tet4, tet10, nodal-pressure", false, false},
    {MaterialModel::neo_hookean, "neo-hookean",
     "compressible neo-Hookean, total Lagrangian, CalculiX's NEO HOOKE: W = mu/2 (I1bar - 3) + kappa/2 (J - 1)^2",
     "as linear: mu and kappa = lambda + 2 mu/3 are its small-strain moduli", hyperelastic_elements, true, false},
    {MaterialModel::ogden, "ogden",
     "compressible N-term Ogden, total Lagrangian, CalculiX's OGDEN: W = sum_i 2 mu_i/alpha_i^2 (sum_k lbar_k^alpha_i - 3) "
     "+ kappa/2 (J - 1)^2",
     "ogden_alpha = [alpha_i] (each != 0) and ogden_mu_Pa = [mu_i] (each > 0; their sum is mu; one term may leave it out "
     "and take mu), with lambda_Pa or poisson for the bulk modulus",
     hyperelastic_elements, true, false},
}};
}  // namespace

std::span<const MaterialModelInfo> material_model_table() { return material_models; }

const MaterialModelInfo& material_model_info(MaterialModel model) {
  for (const auto& row : material_models)
    if (row.model == model) return row;
  return material_models[0];
}

std::string_view material_model_name(MaterialModel model) {
  for (const auto& row : material_models)
    if (row.model == model) return row.name;
  return "?";
}

std::string material_model_table_text() {
  std::string text = "Material laws ([material] model; docs/materials.md):\n";
  for (const auto& row : material_models) {
    text += "  " + std::string(row.name) + std::string(row.name.size() < 12 ? 12 - row.name.size() : 1, ' ') +
            std::string(row.summary) + "\n";
    text += "              keys: " + std::string(row.parameters) + "; elements: " + std::string(row.elements) +
            (row.internal_variables ? "; internal variables" : "") + "\n";
  }
  return text;
}

MaterialModel parse_material_model(std::string_view name) {
  std::vector<std::string> names;
  for (const auto& row : material_models) {
    if (row.name == name) return row.model;
    names.emplace_back(row.name);
  }
  std::string valid;
  for (const auto& n : names) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError("material model '" + std::string(name) + "' is unknown" + did_you_mean(name, names) + " (valid: " + valid +
                   ")");
}

}  // namespace roifem::fem
