#include "mesh/mesh_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/errors.hpp"

namespace roifem::mesh {

namespace {
std::string describe_tet(const TetMesh& mesh, Index e) {
  const Tet& t = mesh.tets[static_cast<std::size_t>(e)];
  std::ostringstream s;
  s << mesh.source << ": tetrahedron " << e << " (nodes " << t[0] << ", " << t[1] << ", " << t[2] << ", " << t[3]
    << ", 0-based)";
  return s.str();
}
}  // namespace

void check_mesh(const TetMesh& mesh) {
  if (mesh.num_tets() == 0) throw InputError(mesh.source + ": the mesh has no tetrahedra");
  if (!mesh.nodes.allFinite()) throw InputError(mesh.source + ": a node coordinate is NaN or infinite");
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
      throw InputError(describe_tet(mesh, e) + " has zero volume (shape quality " + std::to_string(q) + ")");
  }
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
