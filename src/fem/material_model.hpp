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
#include <span>
#include <string_view>

namespace roifem::fem {

enum class MaterialModel { linear, neo_hookean };

struct MaterialModelInfo {
  MaterialModel model;
  std::string_view name;
  std::string_view summary;  ///< one line for --help and the docs
};

/// The one list of laws.
std::span<const MaterialModelInfo> material_model_table();
std::string_view material_model_name(MaterialModel model);
/// InputError naming the valid names (with "did you mean") for an unknown one.
MaterialModel parse_material_model(std::string_view name);

}  // namespace roifem::fem
