// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Models with known structure shared by the tests: the shipped brain as in the paper (base held,
/// the opening's walls pulled apart) and a small cantilever beam, each with its ROI partition.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/fem_model.hpp"
#include "model/prescribed_motion.hpp"
#include "roi/roi.hpp"

namespace roifem::test {

/// The shipped brain, base fixed, the opening's walls pulled apart by 1 mN each.
struct PaperBrain {
  mesh::TetMesh mesh = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  model::FemModel model = model::build_fem_model(
      mesh, fem::material_preset("paper"), {"base"},
      {{"opening_left", Vec3(-1e-3, 0, 0), model::Ramp{0.5}}, {"opening_right", Vec3(1e-3, 0, 0), model::Ramp{0.5}}});
  const fem::DofMap& dofs() const { return *model.dofs; }
  roi::Partition partition(const roi::RoiSpec& spec) const {
    return roi::partition_dofs(model.system.K, *model.dofs, roi::select_roi_nodes(mesh, *model.dofs, spec));
  }
};

/// The paper's ROIs: the `count` free nodes nearest (0, 0, 40) mm.
inline roi::RoiSpec nearest(Index count) {
  return {.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0, 0, 0.040), .count = count, .set = {}};
}

/// A 60 x 20 x 20 mm beam held at x = 0, its far end pulled in z; the ROI is the 27 nodes at that end.
struct Beam {
  mesh::TetMesh mesh = mesh::structured_box_mesh(6, 2, 2, 0.06, 0.02, 0.02);
  model::FemModel model = model::build_fem_model(mesh, fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8), {"x0"},
                                                 {{"x1", Vec3(0, 0, 1e-3), model::Ramp{0.2}}});
  roi::Partition partition() const {
    const roi::RoiSpec spec{.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0.06, 0.01, 0.01), .count = 27, .set = {}};
    return roi::partition_dofs(model.system.K, *model.dofs, roi::select_roi_nodes(mesh, *model.dofs, spec));
  }
};

/// A point mass m on a spring k whose other end a tool moves by g(t) = d min(t / T, 1) in x:
/// m x'' + k x = k g, from rest. Its exact response (undamped) and the tool's force on it.
struct SpringMass {
  double m = 0.5, k = 2 * std::numbers::pi * 2 * std::numbers::pi * 0.5, d = 1e-3, T = 0.4;  // 1 Hz
  double omega() const { return std::sqrt(k / m); }
  double ramp_response(double t) const {  // d/T (t - sin(w t) / w) for t >= 0
    return t <= 0 ? 0.0 : d / T * (t - std::sin(omega() * t) / omega());
  }
  double x(double t) const { return ramp_response(t) - ramp_response(t - T); }
  double g(double t) const { return d * std::min(t / T, 1.0); }
  double force(double t) const { return k * (g(t) - x(t)); }  // on the mass, through the spring

  /// The two nodes' six dofs: the mass's 0-2 and the tool's 3-5.
  model::SecondOrderSystem all() const {
    model::SecondOrderSystem s;
    DenseMatrix K = DenseMatrix::Zero(6, 6);
    K.topLeftCorner(3, 3).diagonal().setConstant(k);
    K.bottomRightCorner(3, 3).diagonal().setConstant(k);
    K.topRightCorner(3, 3).diagonal().setConstant(-k);
    K.bottomLeftCorner(3, 3).diagonal().setConstant(-k);
    s.K = K.sparseView();
    s.M = model::diagonal_matrix(Vector::Constant(6, m));
    s.C = model::diagonal_matrix(Vector::Zero(6));
    s.damping = model::Damping::mass_proportional(0);
    s.load = model::LoadHistory(6);
    return s;
  }
  model::ToolElimination eliminated() const {
    return model::eliminate_tools(
        all(), {{.tool = {.name = "hand", .nodes = {1}, .path = {Vec3(d, 0, 0), model::Ramp{T}}}, .dofs = {3, 4, 5}}});
  }
};

}  // namespace roifem::test
