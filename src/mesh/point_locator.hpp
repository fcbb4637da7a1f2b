// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Where a point lies in a tetrahedral mesh, to read a nodal field there: the tetrahedron that
/// holds it and its barycentric weights, or, for a point outside the mesh, the nearest point of
/// the boundary (a node of a coarse mesh on a curved surface lies a little outside a finer mesh
/// of the same body, whose boundary facets are chords; among equally near boundary points, the one
/// with the largest x, then y, then z). A uniform grid of buckets holds the
/// tetrahedra, so a look-up tests a handful of them.
#include <array>
#include <vector>

#include "common/types.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

struct PointLocation {
  std::array<int, 4> nodes{};
  std::array<double, 4> weights{};  ///< barycentric, summing to 1 (a boundary point uses three)
  double outside_distance = 0;      ///< m from the point to the mesh; 0 inside
  /// On a quadratic mesh, the midpoints of the corner pairs (0 1), (1 2), (2 0), (0 3), (1 3), (2 3)
  /// of `nodes` (-1 where there is none): interpolate() then uses the quadratic shape functions.
  std::array<int, 6> midside{-1, -1, -1, -1, -1, -1};
  bool quadratic = false;
};

class PointLocator {
 public:
  explicit PointLocator(const TetMesh& mesh);
  PointLocation locate(const Vec3& point) const;
  /// The displacement at a location from a field over all nodes (3N): linear in the corners, or
  /// quadratic on a quadratic mesh.
  static Vec3 interpolate(const PointLocation& location, const Eigen::Ref<const Vector>& field);

 private:
  const TetMesh& mesh_;
  Vec3 origin_;
  double cell_ = 1;
  std::array<Index, 3> cells_{};
  std::vector<Index> bucket_start_;  ///< CSR over cells
  std::vector<int> bucket_tets_;
  std::vector<Triangle> boundary_;
  Index cell_index(Index i, Index j, Index k) const { return (k * cells_[1] + j) * cells_[0] + i; }
  std::array<Index, 3> cell_of(const Vec3& p) const;
  PointLocation with_midside(PointLocation at) const;
};

}  // namespace roifem::mesh
