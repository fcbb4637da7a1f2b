// SPDX-License-Identifier: GPL-3.0-or-later
#include "cutting/separated_faces.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <limits>
#include <map>

#include "common/errors.hpp"

namespace roifem::cutting {

namespace {

Vec3 centroid(const mesh::TetMesh& mesh, Index e) {
  const mesh::Tet& t = mesh.tets[static_cast<std::size_t>(e)];
  return 0.25 * (mesh.node(t[0]) + mesh.node(t[1]) + mesh.node(t[2]) + mesh.node(t[3]));
}

/// The sigma at which segment p -> q crosses the strip, or NaN. The ends must lie on opposite sides
/// of the strip's plane, a point within 1e-9 of the segment's length of it counting as on the side its
/// normal edge x move points to (so that a centroid on the plane, as in a structured mesh cut
/// through its cells' middles, is on one side for all its faces); the crossing point's (s, sigma)
/// must lie in the unit square.
double crossing(const SweptStrip& strip, const Vec3& p, const Vec3& q) {
  const Vec3 normal = strip.edge.cross(strip.move);
  const double length = (q - p).norm(), scale = normal.norm() * length;
  if (!(scale > 0)) return std::numeric_limits<double>::quiet_NaN();  // no sweep
  const double dp = (p - strip.origin).dot(normal), dq = (q - strip.origin).dot(normal);
  const bool p_above = dp >= -1e-9 * scale, q_above = dq >= -1e-9 * scale;
  if (p_above == q_above) return std::numeric_limits<double>::quiet_NaN();
  const Vec3 x = p + dp / (dp - dq) * (q - p) - strip.origin;  // on the plane
  // x = s edge + sigma move: the 2 x 2 normal equations.
  const double ee = strip.edge.squaredNorm(), em = strip.edge.dot(strip.move), mm2 = strip.move.squaredNorm();
  const double xe = x.dot(strip.edge), xm = x.dot(strip.move), det = ee * mm2 - em * em;
  const double s = (xe * mm2 - xm * em) / det, sigma = (ee * xm - em * xe) / det;
  const bool inside = s >= 0 && s <= 1 && sigma >= 0 && sigma <= 1;
  return inside ? sigma : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::vector<std::array<Index, 4>> face_neighbours(const mesh::TetMesh& mesh) {
  std::vector<std::array<Index, 4>> across(static_cast<std::size_t>(mesh.num_tets()), {-1, -1, -1, -1});
  std::map<std::array<int, 3>, std::pair<Index, int>> open;  // a face seen once: its tetrahedron and corner
  for (Index e = 0; e < mesh.num_tets(); ++e)
    for (int k = 0; k < 4; ++k) {
      std::array<int, 3> face{};
      for (int j = 0, i = 0; j < 4; ++j)
        if (j != k) face[static_cast<std::size_t>(i++)] = mesh.tets[static_cast<std::size_t>(e)][static_cast<std::size_t>(j)];
      std::sort(face.begin(), face.end());
      const auto [it, first] = open.try_emplace(face, e, k);
      if (first) continue;
      const auto [other, corner] = it->second;
      if (across[static_cast<std::size_t>(other)][static_cast<std::size_t>(corner)] >= 0)
        throw ModelError(mesh.source + ": the face (" + std::to_string(face[0]) + ", " + std::to_string(face[1]) + ", " +
                         std::to_string(face[2]) + ") belongs to three or more tetrahedra (" + std::to_string(other) + ", " +
                         std::to_string(e) + ", ...)");
      across[static_cast<std::size_t>(other)][static_cast<std::size_t>(corner)] = e;
      across[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)] = other;
    }
  return across;
}

std::vector<SeparatedFace> separated_faces(const Blade& blade, const mesh::TetMesh& mesh,
                                           const std::vector<std::array<Index, 4>>& neighbours) {
  if (mesh.is_quadratic())
    throw InputError(mesh.source + ": " + blade.describe() + ": cuts are built for 4-node tetrahedra only");
  refuse_a_degenerate_sweep(blade, mesh);
  // The crossing lies in a or in b, so it is within the strip's box and that tetrahedron's: only
  // the faces of tetrahedra whose boxes meet the strip's are tried (a face in the blade's plane included).
  std::map<std::pair<Index, Index>, double> reached;
  for (const SweptStrip& strip : blade.strips()) {
    Eigen::AlignedBox3d box(strip.origin);
    box.extend(strip.origin + strip.edge).extend(strip.origin + strip.move).extend(strip.origin + strip.edge + strip.move);
    for (Index e = 0; e < mesh.num_tets(); ++e) {
      const mesh::Tet& tet = mesh.tets[static_cast<std::size_t>(e)];
      Eigen::AlignedBox3d tet_box(mesh.node(tet[0]));
      for (int k = 1; k < 4; ++k) tet_box.extend(mesh.node(tet[static_cast<std::size_t>(k)]));
      if (!box.intersects(tet_box)) continue;
      for (const Index other : neighbours[static_cast<std::size_t>(e)]) {
        if (other < 0) continue;
        const std::pair<Index, Index> face{std::min(e, other), std::max(e, other)};
        const double sigma = crossing(strip, centroid(mesh, face.first), centroid(mesh, face.second));
        if (!(sigma >= 0)) continue;
        const double when = blade.start + strip.t0 + sigma * (strip.t1 - strip.t0);
        const auto [it, first] = reached.try_emplace(face, when);
        if (!first) it->second = std::min(it->second, when);
      }
    }
  }
  std::vector<SeparatedFace> faces;
  faces.reserve(reached.size());
  for (const auto& [face, when] : reached) faces.push_back({face.first, face.second, when});
  std::stable_sort(faces.begin(), faces.end(), [](const SeparatedFace& x, const SeparatedFace& y) { return x.time < y.time; });
  return faces;
}

}  // namespace roifem::cutting
