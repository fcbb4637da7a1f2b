// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Problems with known answers shared by the integrator tests: a small cantilever (box mesh, one
/// end fixed, a ramped tip load), a damped oscillator, and the observed order of a method
/// against an exact reference.
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

#include "integrators/factory.hpp"
#include "mesh/box_mesh.hpp"
#include "model/fem_model.hpp"

namespace roifem::integrators::test_problems {

struct Cantilever {
  mesh::TetMesh mesh = mesh::structured_box_mesh(4, 2, 2, 0.04, 0.02, 0.02);
  model::FemModel model;
  Cantilever(double force, double ramp) {
    model = model::build_fem_model(mesh, fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8), {"x0"},
                                   {{"x1", Vec3(0, 0, force), model::Ramp{ramp}}});
  }
  const model::SecondOrderSystem& sys() const { return model.system; }
  model::State rest() const { return model::State::at_rest(sys().size()); }
};

inline Vector run(Integrator& integrator, const model::SecondOrderSystem& sys, model::State s, double T) {
  integrator.reset(sys, s);
  integrator.advance_to(T, s);
  return s.u;
}

/// M = 1, K = 25 (w = 5 rad/s), C = 0.8: one dof, released from u = 1 mm.
inline model::SecondOrderSystem damped_oscillator() {
  model::SecondOrderSystem s;
  s.M = model::diagonal_matrix(Vector::Constant(1, 1.0));
  s.K = model::diagonal_matrix(Vector::Constant(1, 25.0));
  s.C = model::diagonal_matrix(Vector::Constant(1, 0.8));
  s.load = model::LoadHistory(1);
  return s;
}
inline model::State oscillator_start() { return {0, Vector::Constant(1, 1e-3), Vector::Zero(1)}; }

/// Observed order between the last two step sizes, against an exact reference.
inline double observed_order(const std::string& method, const model::SecondOrderSystem& sys, const model::State& start,
                             const Vector& exact, double T, std::initializer_list<double> dts) {
  std::vector<double> errors;
  for (double dt : dts) {
    auto integrator = make_integrator(method, dt);
    errors.push_back((run(*integrator, sys, start, T) - exact).norm() / exact.norm());
  }
  const double order = std::log(errors[errors.size() - 2] / errors.back()) / std::log(2.0);
  std::printf("%-18s errors", method.c_str());
  for (double e : errors) std::printf(" %.2e", e);
  std::printf("  observed order %.2f (theory %d)\n", order, integrator_order(method));
  return order;
}

}  // namespace roifem::integrators::test_problems
