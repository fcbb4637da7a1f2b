// SPDX-License-Identifier: GPL-3.0-or-later
// Sizes from an error estimate (mesh/adapted_size_field.hpp): a mesh whose error is already spread
// evenly keeps its sizes; error gathered at one corner shrinks the sizes there and grows them
// elsewhere, within the per-pass bounds and the gradation; the field is scaled to a uniform mesh's
// node count; bad input is refused.
#include "mesh/adapted_size_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/errors.hpp"
#include "mesh/box_mesh.hpp"

namespace roifem::mesh {
namespace {

double element_size(const TetMesh& mesh, Index e) {
  return std::cbrt(6 * std::numbers::sqrt2 * std::abs(signed_volume(mesh, e)));
}

/// int s^-3 dV over V, each element's mean of s^-3 over its nodes.
double mean_density(const TetMesh& mesh, const Vector& s) {
  double integral = 0;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    double density = 0;
    for (const int a : mesh.tets[static_cast<std::size_t>(e)]) density += std::pow(s[a], -3.0) / 4;
    integral += std::abs(signed_volume(mesh, e)) * density;
  }
  return integral / total_volume(mesh);
}

TEST(AdaptedSizeField, EvenlySpreadErrorKeepsTheMeshAndTheScaleMatchesAUniformMesh) {
  const TetMesh mesh = unstructured_box_mesh(1.0, 0.8, 0.6, 0.1);
  // eta_e^2 = h_e^5: the error of a smooth field on this mesh, already equidistributed.
  Vector error2(mesh.num_tets());
  for (Index e = 0; e < mesh.num_tets(); ++e) error2[e] = std::pow(element_size(mesh, e), 5);
  const AdaptedSizeField field(mesh, error2);
  EXPECT_NEAR(mean_density(mesh, field.nodal_size()), 1.0, 1e-12);
  // One mean size everywhere (the uniform mesher's own spread of sizes, averaged at the nodes).
  EXPECT_LT(field.largest() / field.smallest(), 1.6);
  // Read back at a node and inside.
  EXPECT_NEAR(field.relative_size(mesh.node(7)), field.nodal_size()[7], 1e-12);
  EXPECT_GT(field.relative_size(Vec3(0.5, 0.4, 0.3)), 0.5);
}

TEST(AdaptedSizeField, ErrorAtACornerRefinesThereWithinTheBoundsAndTheGradation) {
  const TetMesh mesh = structured_box_mesh(10, 10, 10, 1.0, 1.0, 1.0);
  Vector error2(mesh.num_tets());
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    Vec3 centre = Vec3::Zero();
    for (const int a : mesh.tets[static_cast<std::size_t>(e)]) centre += mesh.node(a) / 4;
    error2[e] = std::pow(centre.norm(), -3.0);  // a singularity at the origin
  }
  const SizeAdaptation adaptation{.max_refinement = 4, .max_coarsening = 3, .gradation = 0.35};
  const AdaptedSizeField field(mesh, error2, adaptation);
  const Vector& s = field.nodal_size();
  EXPECT_NEAR(mean_density(mesh, s), 1.0, 1e-12);
  const double at_origin = field.relative_size(Vec3::Zero()), far = field.relative_size(Vec3(1, 1, 1));
  EXPECT_GT(far / at_origin, 4.0);
  EXPECT_LE(far / at_origin, 4.0 * 3.0 * (1 + 1e-12));  // one pass: at most 4x finer and 3x coarser
  // Gradation: at most 0.35 size change (m) per metre, in relative sizes.
  const double scale = 1 / field.uniform_size();
  for (const auto& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const double length = (mesh.node(t[a]) - mesh.node(t[b])).norm();
        EXPECT_LE(std::abs(s[t[a]] - s[t[b]]), adaptation.gradation * length * scale * (1 + 1e-9));
      }
}

TEST(AdaptedSizeField, RefusesAnEstimateThatDoesNotFitTheMesh) {
  const TetMesh mesh = structured_box_mesh(2, 2, 2, 1.0, 1.0, 1.0);
  EXPECT_THROW(AdaptedSizeField(mesh, Vector::Ones(3)), InputError);
  Vector negative = Vector::Ones(mesh.num_tets());
  negative[5] = -1;
  try {
    AdaptedSizeField field(mesh, negative);
    FAIL() << "a negative error was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedron 5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace roifem::mesh
