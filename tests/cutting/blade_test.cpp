// SPDX-License-Identifier: GPL-3.0-or-later
// The tetrahedra a blade cuts and when, against an independent construction: a blade whose edge
// spans the mesh sweeps a plane, so a tetrahedron is cut exactly when its vertices lie on both
// sides of the plane, and the blade reaches it when its edge reaches the nearest point of the
// tetrahedron's section by the plane (a polygon whose vertices are where its edges cross the plane).
#include "cutting/blade.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>

#include "common/errors.hpp"
#include "mesh/box_mesh.hpp"
#include "scenario/trajectory_reader.hpp"

namespace roifem::cutting {
namespace {

/// Per tetrahedron straddling the plane x = x0: the least y of its section (its edges' crossings).
std::map<Index, double> section_min_y(const mesh::TetMesh& mesh, double x0) {
  std::map<Index, double> out;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const auto& t = mesh.tets[static_cast<std::size_t>(e)];
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, y = lo;
    for (const int n : t) lo = std::min(lo, mesh.node(n).x()), hi = std::max(hi, mesh.node(n).x());
    if (!(lo < x0 && x0 < hi)) continue;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const Vec3 p = mesh.node(t[static_cast<std::size_t>(a)]), q = mesh.node(t[static_cast<std::size_t>(b)]);
        if ((p.x() - x0) * (q.x() - x0) > 0 || p.x() == q.x()) continue;
        y = std::min(y, p.y() + (x0 - p.x()) / (q.x() - p.x()) * (q.y() - p.y()));
      }
    out[e] = y;
  }
  return out;
}

Blade straight(Vec3 a, Vec3 b, Vec3 move, double start, double duration) {
  Blade blade;
  blade.name = "test";
  blade.edge_a = a;
  blade.edge_b = b;
  blade.start = start;
  blade.path.displacement = move;
  blade.path.ramp.duration = duration;
  return blade;
}

TEST(Blade, CutsTheTetrahedraAPlaneCrossesWhenItsEdgeReachesThem) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(0.02, 0.02, 0.01, 0.004);
  const double x0 = 0.0123, speed = 0.01;  // m/s along +y, from y = -2 mm
  const Blade blade = straight({x0, -0.002, -0.001}, {x0, -0.002, 0.011}, {0, 0.024, 0}, 0.3, 0.024 / speed);
  const std::vector<Crossing> cut = swept_elements(blade, mesh);
  const std::map<Index, double> expected = section_min_y(mesh, x0);
  ASSERT_GT(expected.size(), 20u);
  ASSERT_EQ(cut.size(), expected.size());
  double previous = 0;
  for (const Crossing& c : cut) {
    ASSERT_TRUE(expected.count(c.element)) << "tetrahedron " << c.element << " does not straddle the plane";
    EXPECT_NEAR(c.time, 0.3 + (expected.at(c.element) + 0.002) / speed, 1e-12) << "tetrahedron " << c.element;
    EXPECT_GE(c.time, previous);  // ascending
    previous = c.time;
  }
}

TEST(Blade, ABladeAlongTheMeshFacesOrPastItCutsNothing) {
  // The structured box's tetrahedra lie within its cells: a plane through a layer of nodes only
  // touches their faces.
  const mesh::TetMesh mesh = mesh::structured_box_mesh(4, 2, 2, 0.04, 0.02, 0.02);
  EXPECT_TRUE(swept_elements(straight({0.02, -0.001, -0.001}, {0.02, -0.001, 0.021}, {0, 0.03, 0}, 0, 1), mesh).empty());
  EXPECT_TRUE(swept_elements(straight({0.05, -0.001, -0.001}, {0.05, -0.001, 0.021}, {0, 0.03, 0}, 0, 1), mesh).empty());
  // Half a cell further on, every tetrahedron of that layer of cells (each spans its cell in x).
  EXPECT_EQ(swept_elements(straight({0.025, -0.001, -0.001}, {0.025, -0.001, 0.021}, {0, 0.03, 0}, 0, 1), mesh).size(),
            2u * 2u * 6u);
  // A blade stopping halfway across reaches only the cells it has entered.
  EXPECT_EQ(swept_elements(straight({0.025, -0.001, -0.001}, {0.025, -0.001, 0.021}, {0, 0.0105, 0}, 0, 1), mesh).size(),
            2u * 6u);
}

TEST(Blade, FollowsATrajectoryCornerByCorner) {
  // Across the box along y at 10 mm/s for 1 s, then at 30 mm/s: each tetrahedron the plane x = 15 mm
  // crosses is reached when the edge gets to its section's least y, on the stretch it lies on.
  const mesh::TetMesh mesh = mesh::structured_box_mesh(2, 4, 2, 0.02, 0.04, 0.02);
  Blade blade = straight({0.015, -0.001, -0.001}, {0.015, -0.001, 0.021}, {}, 1.0, 1);
  blade.path = scenario::parse_trajectory("t_s,x_mm,y_mm,z_mm\n0,0,0,0\n1,0,10,0\n2,0,40,0\n", "path.csv");
  EXPECT_EQ(blade.end(), 3.0);
  const std::vector<Crossing> cut = swept_elements(blade, mesh);
  const std::map<Index, double> expected = section_min_y(mesh, 0.015);
  ASSERT_EQ(cut.size(), expected.size());
  int on_second_stretch = 0;
  for (const Crossing& c : cut) {
    const double y = expected.at(c.element) + 0.001;  // the path's travel when the edge gets there
    const double t = 1.0 + (y <= 0.010 ? y / 0.010 : 1.0 + (y - 0.010) / 0.030);
    EXPECT_NEAR(c.time, t, 1e-12) << "tetrahedron " << c.element;
    on_second_stretch += t > 2.0 ? 1 : 0;
  }
  EXPECT_GT(on_second_stretch, 6);
}

TEST(Blade, RefusesAQuadraticMesh) {
  mesh::TetMesh mesh = mesh::structured_box_mesh(1, 1, 1, 0.01, 0.01, 0.01);
  mesh.midside.edges.push_back({0, 1});
  EXPECT_THROW(swept_elements(straight({0.005, 0, 0}, {0.005, 0.01, 0}, {0, 0, 0.01}, 0, 1), mesh), InputError);
}

}  // namespace
}  // namespace roifem::cutting
