#include "experiments/quadratic_tets.hpp"

#include <algorithm>

#include "common/errors.hpp"

namespace roifem::experiments {

namespace {

std::pair<int, int> edge(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

/// The set's boundary triangles, or InputError naming it.
const std::vector<mesh::Triangle>& triangles_of(const mesh::TetMesh& mesh, const std::string& set) {
  const auto& s = mesh.set(set);
  if (s.triangles.empty()) throw InputError(mesh.source + ": set '" + set + "' has no boundary triangles");
  return s.triangles;
}

double area(const mesh::TetMesh& mesh, const mesh::Triangle& t) {
  return 0.5 * (mesh.node(t[1]) - mesh.node(t[0])).cross(mesh.node(t[2]) - mesh.node(t[0])).norm();
}

}  // namespace

int QuadraticTets::midpoint(int a, int b) const {
  const auto key = edge(a, b);
  const auto it = std::lower_bound(edges.begin(), edges.end(), key);
  return it != edges.end() && *it == key ? static_cast<int>(corner_nodes + (it - edges.begin())) : -1;
}

QuadraticTets quadratic_tets(const mesh::TetMesh& mesh) {
  QuadraticTets q;
  q.corner_nodes = mesh.num_nodes();
  q.edges = mesh::unique_edges(mesh);
  q.nodes.resize(3, mesh.num_nodes() + static_cast<Index>(q.edges.size()));
  q.nodes.leftCols(mesh.num_nodes()) = mesh.nodes;
  for (std::size_t k = 0; k < q.edges.size(); ++k)
    q.nodes.col(mesh.num_nodes() + static_cast<Index>(k)) = 0.5 * (mesh.node(q.edges[k].first) + mesh.node(q.edges[k].second));
  q.tets.reserve(mesh.tets.size());
  for (const auto& t : mesh.tets)
    q.tets.push_back({t[0], t[1], t[2], t[3], q.midpoint(t[0], t[1]), q.midpoint(t[1], t[2]), q.midpoint(t[2], t[0]),
                      q.midpoint(t[0], t[3]), q.midpoint(t[1], t[3]), q.midpoint(t[2], t[3])});
  return q;
}

Vector quadratic_set_force(const mesh::TetMesh& mesh, const QuadraticTets& q, const std::string& set, const Vec3& total_force) {
  const auto& triangles = triangles_of(mesh, set);
  double total_area = 0;
  for (const auto& t : triangles) total_area += area(mesh, t);
  Vector f = Vector::Zero(3 * q.nodes.cols());
  for (const auto& t : triangles) {
    const Vec3 share = total_force * area(mesh, t) / total_area / 3;
    for (int k = 0; k < 3; ++k) f.segment<3>(3 * q.midpoint(t[k], t[(k + 1) % 3])) += share;
  }
  return f;
}

Vec3 quadratic_set_mean_displacement(const mesh::TetMesh& mesh, const QuadraticTets& q, const std::string& set, const Vector& u) {
  Vec3 sum = Vec3::Zero();
  double total_area = 0;
  for (const auto& t : triangles_of(mesh, set)) {
    const double a = area(mesh, t);
    for (int k = 0; k < 3; ++k) sum += a / 3 * u.segment<3>(3 * q.midpoint(t[k], t[(k + 1) % 3]));
    total_area += a;
  }
  return sum / total_area;
}

std::vector<int> quadratic_nodes_on(const QuadraticTets& q, const std::vector<int>& linear_nodes) {
  std::vector<int> sorted = linear_nodes;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  auto holds = [&](int n) { return std::binary_search(sorted.begin(), sorted.end(), n); };
  std::vector<int> nodes = sorted;
  for (std::size_t k = 0; k < q.edges.size(); ++k)
    if (holds(q.edges[k].first) && holds(q.edges[k].second))
      nodes.push_back(static_cast<int>(q.corner_nodes) + static_cast<int>(k));
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

}  // namespace roifem::experiments
