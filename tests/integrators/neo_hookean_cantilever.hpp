// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The nonlinear integrator tests' problem: a neo-Hookean cantilever block, and a run of a method
/// on it over a fixed output grid.
#include <algorithm>
#include <cmath>

#include "fem/material.hpp"
#include "integrators/integrator.hpp"
#include "mesh/box_mesh.hpp"
#include "model/fem_model.hpp"

namespace roifem::integrators::testing {

/// A cantilever block (fixed at x = 0) bent by a downward force on its free end, ramped over
/// `ramp` s.
struct NeoHookeanCantilever {
  mesh::TetMesh mesh = mesh::structured_box_mesh(6, 2, 2, 0.06, 0.02, 0.02);
  model::FemModel model;
  NeoHookeanCantilever(double alpha, double force, double ramp, fem::MaterialModel law = fem::MaterialModel::neo_hookean,
                       model::Ramp::Shape shape = model::Ramp::Shape::linear) {
    fem::Material m = fem::Material::from_young_poisson(3000, 0.45, 1000, alpha);
    m.model = law;
    model = model::build_fem_model(mesh, m, {"x0"}, {{"x1", Vec3(0, 0, -force), model::Ramp{ramp, shape}}});
  }
  const model::SecondOrderSystem& sys() const { return model.system; }
  double tip_drop(const model::State& s) const {  // the largest downward displacement (m)
    double drop = 0;
    for (Index i = 2; i < s.u.size(); i += 3) drop = std::max(drop, -s.u[i]);
    return drop;
  }
};

inline constexpr double bending_force = 0.03;  // N: a tip drop of about a third of the length

/// `method` from rest to t_end, output every dt.
inline model::State run_until(const model::SecondOrderSystem& sys, Integrator& method, double t_end, double dt) {
  model::State s = model::State::at_rest(sys.size());
  method.reset(sys, s);
  const long steps = std::lround(t_end / dt);
  for (long k = 1; k <= steps; ++k) method.advance_to(static_cast<double>(k) * dt, s);
  return s;
}

}  // namespace roifem::integrators::testing
