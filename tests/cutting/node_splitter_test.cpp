// SPDX-License-Identifier: GPL-3.0-or-later
// Split mode's topology against an independent expectation: a blade whose edge spans the mesh
// sweeps a plane, so the faces it separates are exactly those between tetrahedra whose centroids
// lie on opposite sides of it, reached when the edge reaches the centroids' segment; once all are
// separated the mesh falls into exactly those two classes, whatever order the faces came in.
#include "cutting/node_splitter.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <set>

#include "cutting/separated_faces.hpp"
#include "cutting/split_plan.hpp"
#include "mesh/box_mesh.hpp"

namespace roifem::cutting {
namespace {

Blade plane_sweep(double x0, double y_from, double y_to, double start, double duration) {
  Blade blade;
  blade.name = "test";
  blade.mode = CutMode::split;
  blade.edge_a = {x0, y_from, -0.001};
  blade.edge_b = {x0, y_from, 0.011};
  blade.start = start;
  blade.path.displacement = {0, y_to - y_from, 0};
  blade.path.ramp.duration = duration;
  return blade;
}

Vec3 centroid(const mesh::TetMesh& mesh, Index e) {
  Vec3 c = Vec3::Zero();
  for (const int n : mesh.tets[static_cast<std::size_t>(e)]) c += mesh.node(n) / 4;
  return c;
}

/// Per node, the piece it belongs to (nodes joined by the tetrahedra).
std::vector<int> pieces(const std::vector<mesh::Tet>& tets, Index nodes) {
  std::vector<int> parent(static_cast<std::size_t>(nodes));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int n) {
    while (parent[static_cast<std::size_t>(n)] != n) n = parent[static_cast<std::size_t>(n)];
    return n;
  };
  for (const auto& t : tets)
    for (int k = 1; k < 4; ++k) parent[static_cast<std::size_t>(root(t[static_cast<std::size_t>(k)]))] = root(t[0]);
  std::vector<int> out(parent.size());
  for (int n = 0; n < nodes; ++n) out[static_cast<std::size_t>(n)] = root(n);
  return out;
}

TEST(SeparatedFaces, AreTheFacesBetweenCentroidsOnEitherSideReachedWhenTheEdgeReachesTheirSegment) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(0.02, 0.02, 0.01, 0.004);
  const double x0 = 0.0123, speed = 0.01;  // m/s along +y, from y = -2 mm
  const Blade blade = plane_sweep(x0, -0.002, 0.022, 0.3, 0.024 / speed);
  const auto neighbours = face_neighbours(mesh);
  const std::vector<SeparatedFace> faces = separated_faces(blade, mesh, neighbours);
  // The expectation, by the centroids' sides and the segment's crossing of the plane.
  std::size_t expected = 0;
  double worst = 0;
  for (Index a = 0; a < mesh.num_tets(); ++a)
    for (const Index b : neighbours[static_cast<std::size_t>(a)]) {
      if (b <= a) continue;
      const Vec3 p = centroid(mesh, a), q = centroid(mesh, b);
      if ((p.x() - x0) * (q.x() - x0) >= 0) continue;
      ++expected;
      const double y = p.y() + (x0 - p.x()) / (q.x() - p.x()) * (q.y() - p.y());
      const auto found = std::find_if(faces.begin(), faces.end(), [&](const SeparatedFace& f) { return f.a == a && f.b == b; });
      ASSERT_NE(found, faces.end()) << a << " " << b;
      worst = std::max(worst, std::abs(found->time - (0.3 + (y + 0.002) / speed)));
    }
  ASSERT_GT(expected, 20u);
  EXPECT_EQ(faces.size(), expected);
  EXPECT_LT(worst, 1e-12);
  EXPECT_TRUE(std::is_sorted(faces.begin(), faces.end(), [](const auto& x, const auto& y) { return x.time < y.time; }));
}

TEST(NodeSplitter, ABladeThroughTheWholeBodyLeavesExactlyTheTwoSidesAndAnyOrderGivesThem) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(0.02, 0.02, 0.01, 0.004);
  const double x0 = 0.0123;
  const std::vector<Blade> blades{plane_sweep(x0, -0.002, 0.022, 0.0, 1.0)};
  const SplitPlan plan = plan_splits(blades, mesh, 1.0);
  ASSERT_GT(plan.num_copies(), 10);
  // In the run's order, a few faces per step, with the reserved copies.
  NodeSplitter splitter(mesh.tets, plan.neighbours, mesh.num_nodes(), plan.copies);
  for (std::size_t i = 0; i < plan.faces.size(); i += 7) {
    std::vector<std::pair<Index, Index>> batch;
    for (std::size_t j = i; j < std::min(i + 7, plan.faces.size()); ++j) batch.emplace_back(plan.faces[j].a, plan.faces[j].b);
    splitter.separate(batch);
  }
  EXPECT_EQ(static_cast<Index>(splitter.copies_made().size()), plan.num_copies());  // the dry run's count, all used
  const std::vector<int> piece = pieces(splitter.tets(), mesh.num_nodes() + plan.num_copies());
  std::set<int> left, right;
  for (Index e = 0; e < mesh.num_tets(); ++e)
    (centroid(mesh, e).x() < x0 ? left : right)
        .insert(piece[static_cast<std::size_t>(splitter.tets()[static_cast<std::size_t>(e)][0])]);
  EXPECT_EQ(left.size(), 1u);
  EXPECT_EQ(right.size(), 1u);
  EXPECT_NE(*left.begin(), *right.begin());
  // Each corner holds its original node or a copy of it; the nodes both sides shared are split.
  std::vector<int> original(static_cast<std::size_t>(mesh.num_nodes() + plan.num_copies()));
  std::iota(original.begin(), original.begin() + mesh.num_nodes(), 0);
  for (Index k = 0; k < plan.num_copies(); ++k)
    original[static_cast<std::size_t>(mesh.num_nodes() + k)] = plan.copy_of[static_cast<std::size_t>(k)];
  std::set<int> on_both;
  std::vector<int> side(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const int s = centroid(mesh, e).x() < x0 ? 0 : 1;
    for (int k = 0; k < 4; ++k) {
      const int n = mesh.tets[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)];
      EXPECT_EQ(original[static_cast<std::size_t>(splitter.tets()[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)])], n);
      if (side[static_cast<std::size_t>(n)] >= 0 && side[static_cast<std::size_t>(n)] != s) on_both.insert(n);
      side[static_cast<std::size_t>(n)] = s;
    }
  }
  EXPECT_GE(plan.num_copies(), static_cast<Index>(on_both.size()));
  // All at once: the same two pieces, the same number of copies.
  NodeSplitter at_once(mesh.tets, plan.neighbours, mesh.num_nodes());
  std::vector<std::pair<Index, Index>> all;
  for (const auto& f : plan.faces) all.emplace_back(f.a, f.b);
  at_once.separate(all);
  EXPECT_EQ(at_once.copies_made().size(), splitter.copies_made().size());
  const std::vector<int> piece_once = pieces(at_once.tets(), mesh.num_nodes() + plan.num_copies());
  for (Index e = 0; e < mesh.num_tets(); ++e)
    EXPECT_EQ(piece_once[static_cast<std::size_t>(at_once.tets()[static_cast<std::size_t>(e)][0])] ==
                  piece_once[static_cast<std::size_t>(at_once.tets()[0][0])],
              piece[static_cast<std::size_t>(splitter.tets()[static_cast<std::size_t>(e)][0])] ==
                  piece[static_cast<std::size_t>(splitter.tets()[0][0])]);
}

TEST(NodeSplitter, ACutThatEndsInsideTheBodyOpensItButLeavesItWholeAtTheFront) {
  // The edge sweeps only half way across: the faces separated end inside, the nodes at the front
  // keep their stars whole, and the mesh stays one piece; behind the front the two sides part.
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(0.02, 0.02, 0.01, 0.004);
  const std::vector<Blade> blades{plane_sweep(0.0123, -0.002, 0.010, 0.0, 1.0)};
  const SplitPlan plan = plan_splits(blades, mesh, 1.0);
  NodeSplitter splitter(mesh.tets, plan.neighbours, mesh.num_nodes(), plan.copies);
  std::vector<std::pair<Index, Index>> all;
  for (const auto& f : plan.faces) all.emplace_back(f.a, f.b);
  const std::vector<Rewire> moved = splitter.separate(all);
  ASSERT_GT(plan.num_copies(), 3);
  EXPECT_EQ(static_cast<Index>(splitter.copies_made().size()), plan.num_copies());
  const std::vector<int> piece = pieces(splitter.tets(), mesh.num_nodes() + plan.num_copies());
  std::set<int> used;
  for (const auto& t : splitter.tets()) used.insert(piece[static_cast<std::size_t>(t[0])]);
  EXPECT_EQ(used.size(), 1u);
  for (const Rewire& r : moved) EXPECT_LT(mesh.node(r.from).y(), 0.010 + 0.004);  // nothing split an element beyond the edge
}

}  // namespace
}  // namespace roifem::cutting
