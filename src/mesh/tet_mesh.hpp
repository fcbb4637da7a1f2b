// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A tetrahedral mesh with named node and element sets.
///   nodes: 3 x #N, metres
///   tets:  #E x 4, 0-based node indices, positively oriented (det[x1-x0, x2-x0, x3-x0] > 0)
/// Named sets come from Gmsh physical groups: a 3D group lists tetrahedra, a 2D group lists
/// boundary triangles, and every set lists its nodes (sorted, unique).
/// A quadratic mesh (mesh/quadratic_mesh.hpp, for the 10-node tetrahedron) also has a node at the
/// midpoint of every edge: the vertices come first, then edge k's midpoint as node
/// num_vertices() + k. Its elements stay straight-sided (`tets` lists their corners, `midside`
/// the rest), triangles list corners, and sets list every node they hold, midpoints included.
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/types.hpp"

namespace roifem::mesh {

using Tet = std::array<int, 4>;
using Triangle = std::array<int, 3>;

struct NamedSet {
  int dim = 0;                      ///< 0..3, the Gmsh physical group's dimension
  std::vector<int> nodes;           ///< sorted, unique
  std::vector<int> tets;            ///< indices into TetMesh::tets (dim 3)
  std::vector<Triangle> triangles;  ///< boundary facets (dim 2)
};

/// The edge-midpoint nodes of a quadratic mesh; empty for a linear one.
struct MidsideNodes {
  std::vector<std::pair<int, int>> edges;  ///< every edge once, (a < b), sorted; edge k's midpoint is node first + k
  Index first = 0;                         ///< the number of vertices
  /// Per tetrahedron, the midpoints of its edges (t0 t1), (t1 t2), (t2 t0), (t0 t3), (t1 t3), (t2 t3):
  /// with the corners, the 10 nodes in Gmsh's and CalculiX's order.
  std::vector<std::array<int, 6>> of_tet;
  /// The midpoint node of edge (a, b), either order; -1 when the mesh has no such edge.
  int at(int a, int b) const;
};

struct TetMesh {
  Eigen::Matrix3Xd nodes;                ///< 3 x #N, metres
  std::vector<Tet> tets;                 ///< #E x 4
  std::map<std::string, NamedSet> sets;  ///< by physical name
  std::string source = "<memory>";       ///< file it came from, for messages
  MidsideNodes midside;                  ///< quadratic meshes only
  /// What reading the file dropped (a set's triangle over a node that no tetrahedron uses), each
  /// naming the file, the set and the node: the commands print them.
  std::vector<std::string> warnings;

  bool is_quadratic() const { return !midside.edges.empty(); }
  /// The tetrahedra's corners: all nodes of a linear mesh, the first ones of a quadratic mesh.
  Index num_vertices() const { return nodes.cols() - static_cast<Index>(midside.edges.size()); }
  Index num_nodes() const { return nodes.cols(); }
  Index num_tets() const { return static_cast<Index>(tets.size()); }
  Vec3 node(int i) const { return nodes.col(i); }
  /// The named set, or InputError listing the sets that exist.
  const NamedSet& set(const std::string& name) const;
};

/// Signed volume of tetrahedron e (positive when correctly oriented).
double signed_volume(const TetMesh& mesh, Index e);
/// Sum of the tetrahedra's volumes.
double total_volume(const TetMesh& mesh);
/// Shape quality 6 sqrt(2) V / l_rms^3: 1 for the regular tetrahedron, 0 for a flat one.
double tet_quality(const TetMesh& mesh, Index e);
/// Boundary faces: those that belong to exactly one tetrahedron, oriented outwards.
std::vector<Triangle> boundary_faces(const TetMesh& mesh);
/// Nodes on the boundary faces (a quadratic mesh's: with their edges' midpoints), sorted.
std::vector<int> boundary_nodes(const TetMesh& mesh);
/// Every edge once, as (a, b) with a < b, sorted.
std::vector<std::pair<int, int>> unique_edges(const TetMesh& mesh);

}  // namespace roifem::mesh
