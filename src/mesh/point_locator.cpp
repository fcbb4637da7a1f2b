// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/point_locator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roifem::mesh {

namespace {

/// The corner pairs of PointLocation::midside.
constexpr std::array<std::array<std::size_t, 2>, 6> location_edges{{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};

/// Barycentric coordinates of p in tetrahedron e.
std::array<double, 4> barycentric(const TetMesh& mesh, const Tet& tet, const Vec3& p) {
  const Vec3 x0 = mesh.node(tet[0]);
  Eigen::Matrix3d J;
  J << mesh.node(tet[1]) - x0, mesh.node(tet[2]) - x0, mesh.node(tet[3]) - x0;
  const Vec3 w = J.partialPivLu().solve(p - x0);
  return {1 - w.sum(), w[0], w[1], w[2]};
}

/// The point of triangle abc nearest to p, as barycentric weights (Ericson, Real-Time Collision
/// Detection, 5.1.5).
std::array<double, 3> closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

}  // namespace

PointLocator::PointLocator(const TetMesh& mesh) : mesh_(mesh), boundary_(boundary_faces(mesh)) {
  const Vec3 lo = mesh.nodes.rowwise().minCoeff(), hi = mesh.nodes.rowwise().maxCoeff();
  const Vec3 extent = (hi - lo).cwiseMax(1e-12);
  // About one tetrahedron per cell.
  cell_ = std::cbrt(extent.prod() / static_cast<double>(std::max<Index>(1, mesh.num_tets())));
  origin_ = lo;
  for (int d = 0; d < 3; ++d) cells_[d] = std::max<Index>(1, static_cast<Index>(std::ceil(extent[d] / cell_)));
  const Index n_cells = cells_[0] * cells_[1] * cells_[2];
  auto for_each_cell = [&](const Tet& tet, auto&& visit) {
    Vec3 a = mesh.node(tet[0]), b = a;
    for (int k = 1; k < 4; ++k) {
      a = a.cwiseMin(mesh.node(tet[k]));
      b = b.cwiseMax(mesh.node(tet[k]));
    }
    const auto c0 = cell_of(a), c1 = cell_of(b);
    for (Index k = c0[2]; k <= c1[2]; ++k)
      for (Index j = c0[1]; j <= c1[1]; ++j)
        for (Index i = c0[0]; i <= c1[0]; ++i) visit(cell_index(i, j, k));
  };
  bucket_start_.assign(static_cast<std::size_t>(n_cells + 1), 0);
  for (const Tet& tet : mesh.tets) for_each_cell(tet, [&](Index c) { ++bucket_start_[static_cast<std::size_t>(c + 1)]; });
  for (Index c = 0; c < n_cells; ++c)
    bucket_start_[static_cast<std::size_t>(c + 1)] += bucket_start_[static_cast<std::size_t>(c)];
  bucket_tets_.resize(static_cast<std::size_t>(bucket_start_.back()));
  std::vector<Index> fill(bucket_start_.begin(), bucket_start_.end() - 1);
  for (Index e = 0; e < mesh.num_tets(); ++e)
    for_each_cell(mesh.tets[static_cast<std::size_t>(e)], [&](Index c) {
      bucket_tets_[static_cast<std::size_t>(fill[static_cast<std::size_t>(c)]++)] = static_cast<int>(e);
    });
}

std::array<Index, 3> PointLocator::cell_of(const Vec3& p) const {
  std::array<Index, 3> c{};
  for (int d = 0; d < 3; ++d)
    c[static_cast<std::size_t>(d)] = std::clamp<Index>(static_cast<Index>(std::floor((p[d] - origin_[d]) / cell_)), 0,
                                                       cells_[static_cast<std::size_t>(d)] - 1);
  return c;
}

PointLocation PointLocator::locate(const Vec3& point) const {
  // Inside: the tetrahedron whose smallest barycentric weight is largest (ties on shared faces).
  const auto c = cell_of(point);
  const Index cell = cell_index(c[0], c[1], c[2]);
  PointLocation best;
  double best_min = -std::numeric_limits<double>::infinity();
  for (Index k = bucket_start_[static_cast<std::size_t>(cell)]; k < bucket_start_[static_cast<std::size_t>(cell + 1)]; ++k) {
    const Tet& tet = mesh_.tets[static_cast<std::size_t>(bucket_tets_[static_cast<std::size_t>(k)])];
    const auto w = barycentric(mesh_, tet, point);
    const double smallest = *std::min_element(w.begin(), w.end());
    if (smallest > best_min) {
      best_min = smallest;
      best.nodes = tet;
      best.weights = w;
    }
  }
  if (best_min >= -1e-10) return with_midside(best);
  // Outside: the nearest boundary point.
  double best_d2 = std::numeric_limits<double>::infinity();
  Vec3 best_point = Vec3::Constant(-std::numeric_limits<double>::infinity());
  for (const Triangle& f : boundary_) {
    const Vec3 a = mesh_.node(f[0]), b = mesh_.node(f[1]), cc = mesh_.node(f[2]);
    const auto w = closest_on_triangle(point, a, b, cc);
    const Vec3 q = w[0] * a + w[1] * b + w[2] * cc;
    const double d2 = (q - point).squaredNorm();
    // Equally near points (a point midway between two walls) go to the largest x, then y, then z,
    // so that every mesh of the body answers from the same side.
    const bool tie = std::abs(d2 - best_d2) <= 1e-9 * best_d2;
    if ((d2 < best_d2 && !tie) ||
        (tie && std::lexicographical_compare(best_point.data(), best_point.data() + 3, q.data(), q.data() + 3))) {
      best_d2 = d2;
      best_point = q;
      best.nodes = {f[0], f[1], f[2], f[2]};
      best.weights = {w[0], w[1], w[2], 0};
    }
  }
  best.outside_distance = std::sqrt(best_d2);
  return with_midside(best);
}

PointLocation PointLocator::with_midside(PointLocation at) const {
  if (!mesh_.is_quadratic()) return at;
  at.quadratic = true;
  for (std::size_t k = 0; k < at.midside.size(); ++k) {
    const int i = location_edges[k][0], j = location_edges[k][1];
    if (at.weights[i] != 0 && at.weights[j] != 0) at.midside[k] = mesh_.midside.at(at.nodes[i], at.nodes[j]);
  }
  return at;
}

Vec3 PointLocator::interpolate(const PointLocation& location, const Eigen::Ref<const Vector>& field) {
  const bool quadratic = location.quadratic;
  Vec3 u = Vec3::Zero();
  for (std::size_t k = 0; k < 4; ++k) {
    const double L = location.weights[k];
    if (L != 0) u += (quadratic ? L * (2 * L - 1) : L) * field.segment<3>(3 * static_cast<Index>(location.nodes[k]));
  }
  for (std::size_t k = 0; k < location.midside.size(); ++k)
    if (location.midside[k] >= 0)
      u += 4 * location.weights[location_edges[k][0]] * location.weights[location_edges[k][1]] *
           field.segment<3>(3 * static_cast<Index>(location.midside[k]));
  return u;
}

}  // namespace roifem::mesh
