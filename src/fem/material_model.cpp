// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/material_model.hpp"

#include <array>
#include <string>
#include <vector>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"

namespace roifem::fem {

namespace {
constexpr std::array<MaterialModelInfo, 2> material_models{{
    {MaterialModel::linear, "linear", "small-strain isotropic elasticity (the paper's): a constant K"},
    {MaterialModel::neo_hookean, "neo-hookean",
     "compressible neo-Hookean, total Lagrangian, CalculiX's NEO HOOKE: W = mu/2 (I1bar - 3) + kappa/2 (J - 1)^2"},
}};
}  // namespace

std::span<const MaterialModelInfo> material_model_table() { return material_models; }

std::string_view material_model_name(MaterialModel model) {
  for (const auto& row : material_models)
    if (row.model == model) return row.name;
  return "?";
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
