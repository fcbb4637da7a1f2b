#pragma once
/// Quadratic tetrahedra on a linear mesh, for CalculiX's C3D10 (experiments/calculix_static.hpp):
/// one node at the midpoint of every edge, so the elements are straight-sided and the body is the
/// linear mesh's own (the comparison with the linear elements is then one of elements alone, not of
/// geometry). Node numbers: the linear mesh's 0..N-1, then one per edge. Per tetrahedron the ten
/// nodes in CalculiX's order: corners 1-4, then the midpoints of edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.
/// A uniform traction on a flat 6-node triangle is carried by its midside nodes alone, a third of
/// the triangle's force each (the corners' consistent share is zero), and the mean displacement of
/// a set is, likewise, the area-weighted third of its midside nodes' displacements.
#include <array>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::experiments {

struct QuadraticTets {
  Eigen::Matrix3Xd nodes;                  ///< m: the linear mesh's nodes, then the midpoints
  std::vector<std::array<int, 10>> tets;   ///< 0-based, CalculiX's order
  Index corner_nodes = 0;                  ///< N: the first N nodes are the linear mesh's
  std::vector<std::pair<int, int>> edges;  ///< the linear mesh's (a < b), sorted; edge k's midpoint is node N + k

  /// The midpoint node of edge (a, b) of the linear mesh; -1 when there is no such edge.
  int midpoint(int a, int b) const;
};

QuadraticTets quadratic_tets(const mesh::TetMesh& mesh);

/// Nodal forces (3 x nodes.cols()) of a total force spread uniformly over the 2D set's area.
Vector quadratic_set_force(const mesh::TetMesh& mesh, const QuadraticTets& q, const std::string& set, const Vec3& total_force);
/// The area-weighted mean displacement of a 2D set; u over every node of q (3 x nodes.cols()).
Vec3 quadratic_set_mean_displacement(const mesh::TetMesh& mesh, const QuadraticTets& q, const std::string& set, const Vector& u);
/// The nodes of q that lie on the given nodes of the linear mesh: those nodes, and the midpoints
/// of edges with both ends among them (sorted, each once).
std::vector<int> quadratic_nodes_on(const QuadraticTets& q, const std::vector<int>& linear_nodes);

}  // namespace roifem::experiments
