// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Split mode's topology: opening faces of a tetrahedral mesh by splitting nodes. Around a node n,
/// its tetrahedra (n's star) are joined across the faces at n that are not separated; when the
/// separated faces break the star into several pieces, n is split: one piece keeps n (the one
/// holding the star's lowest anchored tetrahedron, one at a support or the static part, so that
/// what moves stays clear of them; without one, the lowest tetrahedron's), every other piece gets
/// a copy of n (the same position) in its tetrahedra. No material is removed, no element is made or reshaped: only which node a
/// corner holds changes. Where the separated faces end (the cut's front) the star stays one piece around its nodes, so the mesh
/// stays joined there. Separations only ever break pieces further, so the copies a whole run needs are known by running it once
/// beforehand (a dry run), and reserved.
#include <array>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::cutting {

/// A corner of a tetrahedron moved from one node to another (a copy of the same original node).
struct Rewire {
  Index element = 0;
  int corner = 0;  ///< 0..3
  int from = 0, to = 0;
};

class NodeSplitter {
 public:
  /// `tets`: the mesh's tetrahedra as the blades find them; `neighbours`: their face neighbours
  /// (cutting/separated_faces.hpp); `num_nodes`: the original nodes. `copies`: per original node,
  /// the copies reserved for it, taken in order; empty: a dry run, whose copies are numbered on from
  /// num_nodes as they are made. `anchored`: per tetrahedron, whether its piece should keep the
  /// node (empty: none is). How many copies a node needs does not depend on which piece keeps it.
  NodeSplitter(std::vector<mesh::Tet> tets, std::vector<std::array<Index, 4>> neighbours, Index num_nodes,
               std::vector<std::vector<int>> copies = {}, std::vector<bool> anchored = {});
  /// Separates the faces between the pairs of tetrahedra given (face neighbours, each pair once
  /// overall) and splits the nodes whose stars fall apart. Returns the corners moved, in order.
  /// Throws Error when a node has no copy left (the reservation was not this run's).
  std::vector<Rewire> separate(const std::vector<std::pair<Index, Index>>& faces);
  /// The tetrahedra as the separations left them.
  const std::vector<mesh::Tet>& tets() const { return tets_; }
  /// The copies made so far, as (copy, original), in the order made.
  const std::vector<std::pair<int, int>>& copies_made() const { return made_; }

 private:
  std::vector<mesh::Tet> original_, tets_;
  std::vector<std::array<Index, 4>> neighbours_;
  std::vector<std::array<bool, 4>> separated_;  ///< per tetrahedron, its face opposite corner k
  std::vector<std::vector<Index>> star_;        ///< per original node, its tetrahedra
  std::vector<std::vector<int>> copies_;        ///< per original node, its reserved copies
  std::vector<std::size_t> taken_;              ///< per original node, copies taken
  Index next_copy_;                             ///< a dry run's next copy
  std::vector<bool> anchored_;
  std::vector<std::pair<int, int>> made_;
  void split(int node, std::vector<Rewire>& moved);
};

}  // namespace roifem::cutting
