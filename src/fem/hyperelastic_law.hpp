// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The seam between the hyperelastic laws (fem/material_model.hpp's table) and what evaluates them:
/// the elements, the assembly, the discrete gradient. A law is a type with
///   energy(H), stress(H), excess_stress(H), stress_and_tangent(H, P, A)   of the displacement gradient H,
///   stress_of_strain(E), strain_tangent(E)                              of the Green-Lagrange strain E,
///   mu(), kappa(), deviatoric_part()
/// (NeoHookean, Ogden: each keeps its digits at small strain in its own way). The elements and the
/// discrete gradient are templates over it, instantiated once per law, so that each law's
/// arithmetic is the code it was measured with; the assembly holds one law per material and picks
/// it once per element (std::visit), outside the element's arithmetic.
#include <concepts>
#include <variant>

#include "common/types.hpp"
#include "fem/material.hpp"
#include "fem/neo_hookean.hpp"
#include "fem/ogden.hpp"

namespace roifem::fem {

template <class Law>
concept HyperelasticLawType = requires(const Law& law, const Mat3& X, Mat3& P, Mat9& A) {
  { law.energy(X) } -> std::convertible_to<double>;
  { law.stress(X) } -> std::convertible_to<Mat3>;
  { law.excess_stress(X) } -> std::convertible_to<Mat3>;
  law.stress_and_tangent(X, P, A);
  { law.stress_of_strain(X) } -> std::convertible_to<Mat3>;
  { law.strain_tangent(X) } -> std::convertible_to<Mat9>;
  { law.mu() } -> std::convertible_to<double>;
  { law.kappa() } -> std::convertible_to<double>;
  { law.deviatoric_part() } -> std::same_as<Law>;
};

/// One of the laws (the order of MaterialModel's hyperelastic rows).
using HyperelasticLaw = std::variant<NeoHookean, Ogden>;

/// A material's law: Ogden for model ogden; neo-Hookean otherwise (a linear material's element,
/// where an assembly is given one, by the law whose small-strain limit it is).
HyperelasticLaw hyperelastic_law(const Material& material);

}  // namespace roifem::fem
