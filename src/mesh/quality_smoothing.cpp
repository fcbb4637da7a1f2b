// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/quality_smoothing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace roifem::mesh {

namespace {

double star_quality(const TetMesh& mesh, const std::vector<int>& star) {
  double worst = std::numeric_limits<double>::infinity();
  for (int e : star) worst = std::min(worst, signed_volume(mesh, e) > 0 ? tet_quality(mesh, e) : -1.0);
  return worst;
}

double min_quality(const TetMesh& mesh) {
  double worst = std::numeric_limits<double>::infinity();
  for (Index e = 0; e < mesh.num_tets(); ++e) worst = std::min(worst, tet_quality(mesh, e));
  return worst;
}

Vec3 face_normal(const TetMesh& mesh, const Triangle& t) {
  return (mesh.node(t[1]) - mesh.node(t[0])).cross(mesh.node(t[2]) - mesh.node(t[0])).normalized();
}

/// A node and what a move of it must respect: its tetrahedra, and (a boundary node) its boundary
/// triangles with their normals before any move.
struct Star {
  std::vector<int> tets;
  std::vector<Triangle> faces;
  std::vector<Vec3> normals;
};

/// Tries the node at `candidate`; keeps it (and returns true) if the star's worst quality rises
/// and no boundary triangle turns by more than the allowed angle (cosine: min_cos) from where it started.
bool try_move(TetMesh& mesh, int node, const Star& star, const Vec3& candidate, double min_cos, double& best) {
  const Vec3 old = mesh.node(node);
  mesh.nodes.col(node) = candidate;
  double q = star_quality(mesh, star.tets);
  for (std::size_t f = 0; f < star.faces.size(); ++f)
    if (face_normal(mesh, star.faces[f]).dot(star.normals[f]) < min_cos) q = -1;
  if (q > best + 1e-12) {
    best = q;
    return true;
  }
  mesh.nodes.col(node) = old;
  return false;
}

}  // namespace

SmoothingReport smooth_poor_tetrahedra(TetMesh& mesh, double below, int sweeps,
                                       const std::function<Vec3(const Vec3&)>& project_to_boundary, double max_turn_deg) {
  const double min_cos = std::cos(max_turn_deg / 180.0 * 3.141592653589793);
  SmoothingReport report;
  report.quality_min_before = min_quality(mesh);
  std::vector<Star> stars(static_cast<std::size_t>(mesh.num_nodes()));
  for (Index e = 0; e < mesh.num_tets(); ++e)
    for (int n : mesh.tets[static_cast<std::size_t>(e)]) stars[static_cast<std::size_t>(n)].tets.push_back(static_cast<int>(e));
  std::vector<bool> on_boundary(static_cast<std::size_t>(mesh.num_nodes()), false);
  for (const Triangle& t : boundary_faces(mesh))
    for (int n : t) {
      on_boundary[static_cast<std::size_t>(n)] = true;
      stars[static_cast<std::size_t>(n)].faces.push_back(t);
      stars[static_cast<std::size_t>(n)].normals.push_back(face_normal(mesh, t));
    }
  const bool slide = static_cast<bool>(project_to_boundary);
  auto place = [&](int node, const Vec3& x) { return on_boundary[static_cast<std::size_t>(node)] ? project_to_boundary(x) : x; };

  for (int sweep = 0; sweep < sweeps; ++sweep) {
    Index moved = 0;
    for (Index e = 0; e < mesh.num_tets(); ++e) {
      if (tet_quality(mesh, e) >= below) continue;
      for (int node : mesh.tets[static_cast<std::size_t>(e)]) {
        if (on_boundary[static_cast<std::size_t>(node)] && !slide) continue;
        const Star& star = stars[static_cast<std::size_t>(node)];
        double best = star_quality(mesh, star.tets);
        // The centroid of the star's other nodes (Laplacian), then a pattern search along the axes
        // with shrinking steps, scaled by the star's mean edge length.
        Vec3 centroid = Vec3::Zero();
        double length = 0;
        int count = 0;
        for (int s : star.tets)
          for (int other : mesh.tets[static_cast<std::size_t>(s)])
            if (other != node) {
              centroid += mesh.node(other);
              length += (mesh.node(other) - mesh.node(node)).norm();
              ++count;
            }
        centroid /= count;
        length /= count;
        bool improved = try_move(mesh, node, star, place(node, centroid), min_cos, best);
        for (double step = 0.2 * length; step > 0.005 * length; step *= 0.5) {
          bool again = true;
          while (again) {
            again = false;
            for (int axis = 0; axis < 3; ++axis)
              for (double sign : {1.0, -1.0}) {
                Vec3 candidate = mesh.node(node);
                candidate[axis] += sign * step;
                if (try_move(mesh, node, star, place(node, candidate), min_cos, best)) improved = again = true;
              }
          }
        }
        if (improved) ++moved;
      }
    }
    report.moves += moved;
    if (moved == 0) break;
  }
  report.quality_min_after = min_quality(mesh);
  return report;
}

Index remove_boundary_caps(TetMesh& mesh, double below) {
  auto key = [](int a, int b, int c) {
    std::array<int, 3> k{a, b, c};
    std::sort(k.begin(), k.end());
    return k;
  };
  std::map<std::array<int, 3>, int> face_count;
  for (const Tet& t : mesh.tets)
    for (int skip = 0; skip < 4; ++skip) {
      int f[3], n = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) f[n++] = t[static_cast<std::size_t>(a)];
      ++face_count[key(f[0], f[1], f[2])];
    }
  std::set<std::pair<int, int>> boundary_edges;
  for (const auto& [face, count] : face_count)
    if (count == 1)
      for (int a = 0; a < 3; ++a)
        boundary_edges.insert(std::minmax(face[static_cast<std::size_t>(a)], face[static_cast<std::size_t>((a + 1) % 3)]));
  std::vector<int> uses(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (const Tet& t : mesh.tets)
    for (int n : t) ++uses[static_cast<std::size_t>(n)];
  std::vector<bool> removed(mesh.tets.size(), false);
  Index count = 0;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    if (tet_quality(mesh, e) >= below) continue;
    const Tet& t = mesh.tets[static_cast<std::size_t>(e)];
    std::vector<int> outer;  // the nodes opposite the boundary faces
    for (int skip = 0; skip < 4; ++skip) {
      int f[3], n = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) f[n++] = t[static_cast<std::size_t>(a)];
      if (face_count[key(f[0], f[1], f[2])] == 1) outer.push_back(t[static_cast<std::size_t>(skip)]);
    }
    // Two boundary faces: the nodes opposite them span the edge the two inner faces share.
    if (outer.size() != 2 || boundary_edges.count(std::minmax(outer[0], outer[1])) > 0) continue;
    if (std::any_of(t.begin(), t.end(), [&](int n) { return uses[static_cast<std::size_t>(n)] < 2; })) continue;
    removed[static_cast<std::size_t>(e)] = true;
    for (int n : t) --uses[static_cast<std::size_t>(n)];
    ++count;
    // The two inner faces join the boundary, and with them the edge they share.
    boundary_edges.insert(std::minmax(outer[0], outer[1]));
    for (int skip = 0; skip < 4; ++skip) {
      int f[3], n = 0;
      for (int a = 0; a < 4; ++a)
        if (a != skip) f[n++] = t[static_cast<std::size_t>(a)];
      auto& c = face_count[key(f[0], f[1], f[2])];
      c = c == 1 ? 0 : 1;
    }
  }
  std::vector<Tet> kept;
  kept.reserve(mesh.tets.size() - static_cast<std::size_t>(count));
  for (std::size_t e = 0; e < mesh.tets.size(); ++e)
    if (!removed[e]) kept.push_back(mesh.tets[e]);
  mesh.tets = std::move(kept);
  return count;
}

}  // namespace roifem::mesh
