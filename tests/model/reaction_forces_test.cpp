// SPDX-License-Identifier: GPL-3.0-or-later
// The supports' reactions against global equilibrium: in a static state the reactions balance the
// loads, force and moment (K annihilates rigid translations and rotations), for both elements and
// with materials by region; and a tool's nodes are not counted among the fixed ones.
#include <gtest/gtest.h>

#include "fem/static_solve.hpp"
#include "mesh/box_mesh.hpp"
#include "model/reaction_forces.hpp"

namespace roifem::model {
namespace {

struct Balance {
  Vec3 force_gap, moment_gap;
  double force_scale, moment_scale;
};

/// Solves K u = f at the end of the ramp and compares the reactions with the loads.
Balance static_balance(const mesh::TetMesh& mesh, const FemModel& model) {
  const Vector f_free = model.system.load.at(10.0);
  const Vector u_all = model.dofs->expand(fem::solve_static(model.system.K, f_free, *model.dofs));
  const Vector f_all = model.dofs->expand_homogeneous(f_free);
  const ReactionForces reactions(model);
  const Vector r = reactions.nodal(u_all);
  Vec3 load = Vec3::Zero(), load_moment = Vec3::Zero(), reaction_moment = Vec3::Zero();
  for (Index n = 0; n < mesh.num_nodes(); ++n) {
    load += f_all.segment<3>(3 * n);
    load_moment += mesh.node(n).cross(Vec3(f_all.segment<3>(3 * n)));
  }
  for (std::size_t i = 0; i < reactions.nodes().size(); ++i)
    reaction_moment += mesh.node(reactions.nodes()[i]).cross(Vec3(r.segment<3>(3 * static_cast<Index>(i))));
  return {reactions.total(u_all) + load, reaction_moment + load_moment, load.norm(), load_moment.norm()};
}

TEST(ReactionForces, BalanceTheLoadsInForceAndMomentForBothElements) {
  const mesh::TetMesh mesh = mesh::structured_box_mesh(4, 3, 5, 0.04, 0.03, 0.05);
  const std::vector<SetLoad> loads{{.set = "z1", .force = Vec3(0.3, -0.2, -1.0), .ramp = {.duration = 1.0}},
                                   {.set = "x1", .force = Vec3(0.0, 0.5, 0.1), .ramp = {.duration = 1.0}}};
  for (const fem::Element element : {fem::Element::tet4, fem::Element::nodal_pressure}) {
    const FemModel model =
        build_fem_model(mesh, fem::Material::from_young_poisson(3000, 0.45, 1000, 0), {"z0"}, loads, {}, element);
    const Balance b = static_balance(mesh, model);
    EXPECT_LT(b.force_gap.norm(), 1e-10 * b.force_scale) << fem::element_name(element);
    EXPECT_LT(b.moment_gap.norm(), 1e-10 * b.moment_scale) << fem::element_name(element);
    std::printf("%s: |sum R + sum f| = %.1e N of %.3f N; moment gap %.1e N m of %.3e N m\n",
                std::string(fem::element_name(element)).c_str(), b.force_gap.norm(), b.force_scale, b.moment_gap.norm(),
                b.moment_scale);
  }
}

TEST(ReactionForces, UniformCompressionSplitsTheLoadByTributaryArea) {
  // A column under uniform pressure on top, its bottom on rollers except one node fully held: a
  // uniform stress state, which linear tetrahedra represent exactly, so each bottom node carries
  // the pressure times its tributary area (lumped on the P1 face), and the total is the load.
  const double lx = 0.02, ly = 0.03, lz = 0.05, F = 2.0;
  const mesh::TetMesh mesh = mesh::structured_box_mesh(2, 3, 4, lx, ly, lz);
  const FemModel model = build_fem_model(mesh, fem::Material::from_young_poisson(5000, 0.3, 1000, 0), {"z0"},
                                         {{.set = "z1", .force = Vec3(0, 0, -F), .ramp = {.duration = 1.0}}});
  const Vector u_all = model.dofs->expand(fem::solve_static(model.system.K, model.system.load.at(1.0), *model.dofs));
  const ReactionForces reactions(model);
  EXPECT_EQ(reactions.nodes().size(), mesh.set("z0").nodes.size());
  EXPECT_NEAR(reactions.total(u_all).z(), F, 1e-12 * F);
  EXPECT_LT(reactions.total(u_all).head<2>().norm(), 1e-12 * F);
}

TEST(ReactionForces, LeaveAToolsNodesOut) {
  const mesh::TetMesh mesh = mesh::structured_box_mesh(3, 3, 3, 0.03, 0.03, 0.03);
  SetTool tool{.name = "pusher", .set = "z1"};
  tool.path.displacement = Vec3(0, 0, -1e-3);
  tool.path.ramp = {.duration = 1.0};
  const FemModel model = build_fem_model(mesh, fem::Material::from_young_poisson(5000, 0.3, 1000, 0), {"z0"}, {}, {tool});
  const ReactionForces reactions(model);
  EXPECT_EQ(reactions.nodes().size(), mesh.set("z0").nodes.size());
  // The tool pushes down; at rest the base pushes back with the tool's force (Newton's third law).
  const Vector u_free = fem::solve_static(model.system.K, model.system.load.at(1.0), *model.dofs);
  const Vector u_all = model.displacement(u_free, 1.0);
  const Vector tool_force = model.tools.forces(u_free, 1.0);
  EXPECT_LT((reactions.total(u_all) + Vec3(tool_force.head<3>())).norm(), 1e-10 * tool_force.norm());
  EXPECT_LT(tool_force.z(), 0);
}

}  // namespace
}  // namespace roifem::model
