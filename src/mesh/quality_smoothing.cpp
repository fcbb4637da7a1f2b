#include "mesh/quality_smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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
/// and no boundary triangle turns by more than 10 degrees from where it started.
bool try_move(TetMesh& mesh, int node, const Star& star, const Vec3& candidate, double& best) {
  const Vec3 old = mesh.node(node);
  mesh.nodes.col(node) = candidate;
  double q = star_quality(mesh, star.tets);
  for (std::size_t f = 0; f < star.faces.size(); ++f)
    if (face_normal(mesh, star.faces[f]).dot(star.normals[f]) < std::cos(10.0 / 180.0 * 3.141592653589793)) q = -1;
  if (q > best + 1e-12) {
    best = q;
    return true;
  }
  mesh.nodes.col(node) = old;
  return false;
}

}  // namespace

SmoothingReport smooth_poor_tetrahedra(TetMesh& mesh, double below, int sweeps,
                                       const std::function<Vec3(const Vec3&)>& project_to_boundary) {
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
        bool improved = try_move(mesh, node, star, place(node, centroid), best);
        for (double step = 0.2 * length; step > 0.005 * length; step *= 0.5) {
          bool again = true;
          while (again) {
            again = false;
            for (int axis = 0; axis < 3; ++axis)
              for (double sign : {1.0, -1.0}) {
                Vec3 candidate = mesh.node(node);
                candidate[axis] += sign * step;
                if (try_move(mesh, node, star, place(node, candidate), best)) improved = again = true;
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

}  // namespace roifem::mesh
