// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/mesh_checks.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::mesh {

namespace {
std::string describe_tet(const TetMesh& mesh, Index e) {
  const Tet& t = mesh.tets[static_cast<std::size_t>(e)];
  std::ostringstream s;
  s << mesh.source << ": tetrahedron " << e << " (nodes " << t[0] << ", " << t[1] << ", " << t[2] << ", " << t[3] << ", 0-based)";
  return s.str();
}
/// Two nodes closer than 1e-10 of the bounding box's diagonal are one point given twice: a seam
/// (meshes merged without removing duplicates) that leaves the two sides unconnected. Found in
/// O(n) by hashing each node into a grid of that spacing and looking in the 27 cells around it.
void check_no_coincident_nodes(const TetMesh& mesh) {
  if (mesh.num_nodes() < 2) return;
  const Vec3 lo = mesh.nodes.rowwise().minCoeff();
  const double tolerance = 1e-10 * (mesh.nodes.rowwise().maxCoeff() - lo).norm();
  if (!(tolerance > 0)) return;
  using Cell = std::array<long long, 3>;
  struct CellHash {
    std::size_t operator()(const Cell& c) const {
      return std::hash<long long>()(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
    }
  };
  std::unordered_map<Cell, std::vector<Index>, CellHash> grid;
  grid.reserve(static_cast<std::size_t>(mesh.num_nodes()));
  auto cell_of = [&](Index n) {
    const Vec3 c = ((mesh.nodes.col(n) - lo) / tolerance).array().floor();
    return Cell{static_cast<long long>(c[0]), static_cast<long long>(c[1]), static_cast<long long>(c[2])};
  };
  for (Index n = 0; n < mesh.num_nodes(); ++n) {
    const Cell c = cell_of(n);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (Index other : it->second)
            if ((mesh.nodes.col(n) - mesh.nodes.col(other)).cwiseAbs().maxCoeff() <= tolerance) {
              std::ostringstream s;
              s.precision(9);
              s << mesh.source << ": nodes " << other << " and " << n << " (0-based) coincide at (" << 1e3 * mesh.nodes(0, n)
                << ", " << 1e3 * mesh.nodes(1, n) << ", " << 1e3 * mesh.nodes(2, n)
                << ") mm: a seam that leaves the two sides unconnected (merge duplicate nodes, e.g. Gmsh's Coherence)";
              throw InputError(s.str());
            }
        }
    grid[c].push_back(n);
  }
}
}  // namespace

void check_mesh(const TetMesh& mesh) {
  if (mesh.num_tets() == 0) throw InputError(mesh.source + ": the mesh has no tetrahedra");
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (!mesh.nodes.col(n).allFinite())
      throw InputError(mesh.source + ": node " + std::to_string(n) + " (0-based) has a NaN or infinite coordinate");
  for (Index e = 0; e < mesh.num_tets(); ++e)
    for (int n : mesh.tets[static_cast<std::size_t>(e)])
      if (n < 0 || n >= mesh.num_nodes())
        throw InputError(describe_tet(mesh, e) + " names node " + std::to_string(n) + ", but the mesh has " +
                         std::to_string(mesh.num_nodes()) + " nodes");
  constexpr double degenerate_quality = 1e-6;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    if (!std::isfinite(signed_volume(mesh, e)))
      throw InputError(describe_tet(mesh, e) + ": its volume overflows (coordinates too large)");
    const double q = tet_quality(mesh, e);
    if (q < 0) throw InputError(describe_tet(mesh, e) + " is inverted (negative volume)");
    // !(q >= ...) also catches NaN: a tetrahedron whose nodes coincide (found by fuzzing).
    if (!(q >= degenerate_quality))
      throw InputError(describe_tet(mesh, e) + " has zero volume (shape quality " + number_text(q) + ")");
  }
  check_no_coincident_nodes(mesh);  // after the volumes: every coordinate is finite and bounded
}

MeshStatistics mesh_statistics(const TetMesh& mesh) {
  MeshStatistics s;
  s.nodes = mesh.num_nodes();
  s.tets = mesh.num_tets();
  s.volume = total_volume(mesh);
  std::vector<double> q(static_cast<std::size_t>(mesh.num_tets()));
  for (Index e = 0; e < mesh.num_tets(); ++e) q[static_cast<std::size_t>(e)] = tet_quality(mesh, e);
  if (!q.empty()) {
    auto mid = q.begin() + static_cast<std::ptrdiff_t>(q.size() / 2);
    std::nth_element(q.begin(), mid, q.end());
    s.quality_median = *mid;
    s.quality_min = *std::min_element(q.begin(), q.end());
  }
  if (mesh.num_nodes() > 0) {
    s.box_min = mesh.nodes.rowwise().minCoeff();
    s.box_max = mesh.nodes.rowwise().maxCoeff();
  }
  return s;
}

}  // namespace roifem::mesh
