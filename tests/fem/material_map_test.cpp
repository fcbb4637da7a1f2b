// SPDX-License-Identifier: GPL-3.0-or-later
// Materials by region: a bar of two materials in series (exact in the P1 space with nu = 0:
// the displacement is piecewise linear, kinked at the interface, which lies on element faces),
// lumped mass against sum rho_e V_e, and a region map of one material giving the uniform K (tet4:
// bit for bit; nodal-pressure: to round-off, its nodal kappa is then a weighted mean).
#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/element.hpp"
#include "fem/loads.hpp"
#include "fem/material_map.hpp"
#include "fem/static_solve.hpp"
#include "mesh/box_mesh.hpp"

namespace roifem::fem {
namespace {

/// A 10 x 1 x 1 cm bar of 20 x 2 x 2 cells and the 3D set "near" of its tetrahedra with x < L1.
mesh::TetMesh two_part_bar(double L, double L1) {
  mesh::TetMesh bar = mesh::structured_box_mesh(20, 2, 2, L, 0.01, 0.01);
  mesh::NamedSet near;
  near.dim = 3;
  for (int e = 0; e < bar.num_tets(); ++e) {
    Vec3 centre = Vec3::Zero();
    for (int n : bar.tets[static_cast<std::size_t>(e)]) centre += bar.node(n) / 4;
    if (centre.x() < L1) near.tets.push_back(e);
  }
  bar.sets["near"] = near;
  return bar;
}

TEST(MaterialMap, TwoMaterialsInSeriesStretchAsTheirCompliancesAdd) {
  const double L = 0.1, L1 = 0.04, area = 1e-4, F = 0.5, E1 = 2000, E2 = 7000;
  const mesh::TetMesh bar = two_part_bar(L, L1);
  const Material soft = Material::from_young_poisson(E1, 0.0, 1000, 1), stiff = Material::from_young_poisson(E2, 0.0, 1100, 1);
  const MaterialMap materials(bar, stiff, {{.set = "near", .material = soft, .name = "soft"}});
  Constraints constraints(bar.num_nodes());
  for (int n : bar.set("x0").nodes) constraints.prescribe(n, 0);
  for (int n : bar.set("y0").nodes) constraints.prescribe(n, 1);
  for (int n : bar.set("z0").nodes) constraints.prescribe(n, 2);
  const DofMap dofs(constraints);
  const Vector f = dofs.restrict_to_free(set_force(bar, "x1", Vec3(F, 0, 0)));
  const Vector u = dofs.expand(solve_static(StiffnessAssembler(bar, dofs).stiffness(materials), f, dofs));
  const double stress = F / area;
  double worst = 0;
  for (int n = 0; n < bar.num_nodes(); ++n) {
    const double x = bar.node(n).x();
    const double exact = x <= L1 ? stress * x / E1 : stress * (L1 / E1 + (x - L1) / E2);
    worst = std::max(worst, (u.segment<3>(3 * n) - Vec3(exact, 0, 0)).norm());
  }
  EXPECT_LT(worst / (stress * (L1 / E1 + (L - L1) / E2)), 1e-10);

  // Lumped mass: each tetrahedron's own rho.
  const Vector m = lumped_node_mass(bar, materials);
  EXPECT_NEAR(m.sum(), (1000 * L1 + 1100 * (L - L1)) * area, 1e-12);
  const std::vector<Index> counts = materials.counts(bar.num_tets());
  EXPECT_EQ(counts[1], static_cast<Index>(bar.set("near").tets.size()));
}

TEST(MaterialMap, OneMaterialInRegionsGivesTheUniformMatrix) {
  const mesh::TetMesh bar = two_part_bar(0.1, 0.04);
  Constraints constraints(bar.num_nodes());
  for (int n : bar.set("x0").nodes) constraints.fix_node(n);
  const DofMap dofs(constraints);
  const Material brain = material_preset("brain");
  const MaterialMap regions(bar, brain, {{.set = "near", .material = brain, .name = "brain"}});
  for (Element element : {Element::tet4, Element::nodal_pressure}) {
    const SparseMatrix uniform = stiffness(bar, dofs, brain, element);
    const SparseMatrix by_region = stiffness(bar, dofs, regions, element);
    ASSERT_EQ(uniform.nonZeros(), by_region.nonZeros());
    const double difference = (uniform - by_region).norm();
    if (element == Element::tet4)
      EXPECT_EQ(difference, 0.0);
    else
      EXPECT_LT(difference, 1e-12 * uniform.norm()) << element_name(element);
  }
}

TEST(MaterialMap, RefusesA2dSetAMissingSetAndAnotherDamping) {
  const mesh::TetMesh bar = two_part_bar(0.1, 0.04);
  const Material brain = material_preset("brain");
  Material damped = brain;
  damped.alpha = 2 * brain.alpha;
  auto message = [&](const std::vector<RegionMaterial>& regions) {
    try {
      MaterialMap map(bar, brain, regions);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("<no InputError>");
  };
  EXPECT_NE(message({{.set = "x1", .material = brain, .name = ""}}).find("'x1' is a 2D set"), std::string::npos);
  EXPECT_NE(message({{.set = "nowhere", .material = brain, .name = ""}}).find("nowhere"), std::string::npos);
  EXPECT_NE(message({{.set = "near", .material = damped, .name = ""}}).find("one damping rate holds for the whole brain"),
            std::string::npos);
}

}  // namespace
}  // namespace roifem::fem
