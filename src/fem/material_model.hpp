// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The constitutive laws a material takes (the scenario's `[material] model` key): one table that
/// the parser, --help and the docs read.
///   linear        small-strain isotropic elasticity, sigma = lambda tr(eps) I + 2 mu eps: the paper's,
///                 a constant K (fem/tet4.hpp, fem/tet10.hpp)
///   neo-hookean   compressible neo-Hookean hyperelasticity, total Lagrangian, in CalculiX's form
///                 (*HYPERELASTIC, NEO HOOKE): W = C10 (I1bar - 3) + (J - 1)^2 / D1 with C10 = mu/2,
///                 D1 = 2/kappa, kappa = lambda + 2 mu/3 (fem/neo_hookean.hpp); a force f_int(u) and
///                 its tangent K_t(u). At small strain it is the linear law with the same lambda, mu.
///   ogden         compressible N-term Ogden hyperelasticity in CalculiX's form (*HYPERELASTIC, OGDEN):
///                 W = sum_i 2 mu_i / alpha_i^2 (lbar_1^alpha_i + lbar_2^alpha_i + lbar_3^alpha_i - 3)
///                 + (J - 1)^2 / D1 (fem/ogden.hpp); sum_i mu_i = mu, D1 = 2/kappa as neo-Hookean's.
///                 Brain tissue (Budday et al. 2017): alpha near -20, compression stiffer than tension.
/// The hyperelastic laws take the same elements and integrators (fem/hyperelastic_law.hpp).
#include <span>
#include <string>
#include <string_view>

namespace roifem::fem {

enum class MaterialModel { linear, neo_hookean, ogden };

struct MaterialModelInfo {
  MaterialModel model;
  std::string_view name;
  std::string_view summary;     ///< one line for --help and the docs
  std::string_view parameters;  ///< the [material] keys beyond the common ones, with their domains
  std::string_view elements;    ///< the elements that take it
  bool hyperelastic;            ///< a force f_int(u) and tangent K_t(u), not a constant K
  bool internal_variables;      ///< carries internal variables (states of the ODE beside u and v)
};

/// The one list of laws.
std::span<const MaterialModelInfo> material_model_table();
const MaterialModelInfo& material_model_info(MaterialModel model);
std::string_view material_model_name(MaterialModel model);
/// The table as --help prints it: each law's line, keys and elements.
std::string material_model_table_text();
/// InputError naming the valid names (with "did you mean") for an unknown one.
MaterialModel parse_material_model(std::string_view name);

}  // namespace roifem::fem
