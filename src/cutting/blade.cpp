// SPDX-License-Identifier: GPL-3.0-or-later
#include "cutting/blade.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <limits>

#include "common/errors.hpp"
#include "common/format.hpp"

namespace roifem::cutting {

namespace {

/// A point of the parameter square: s along the edge, sigma along the path's segment.
struct ParameterPoint {
  double s, sigma;
};
using Polygon = std::vector<ParameterPoint>;

/// lambda(s, sigma) = c + e s + f sigma: a barycentric coordinate over a parallelogram.
struct AffineCoordinate {
  double c, e, f;
  double at(const ParameterPoint& p) const { return c + e * p.s + f * p.sigma; }
};

/// The polygon's part where lambda >= floor (Sutherland-Hodgman against one half-plane).
Polygon clip(const Polygon& polygon, const AffineCoordinate& lambda, double floor) {
  Polygon out;
  out.reserve(polygon.size() + 1);
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const ParameterPoint& p = polygon[i];
    const ParameterPoint& q = polygon[(i + 1) % polygon.size()];
    const double lp = lambda.at(p) - floor, lq = lambda.at(q) - floor;
    if (lp >= 0) out.push_back(p);
    if ((lp >= 0) != (lq >= 0)) {
      const double w = lp / (lp - lq);
      out.push_back({p.s + w * (q.s - p.s), p.sigma + w * (q.sigma - p.sigma)});
    }
  }
  return out;
}

double area(const Polygon& polygon) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const ParameterPoint& p = polygon[i];
    const ParameterPoint& q = polygon[(i + 1) % polygon.size()];
    twice += p.s * q.sigma - q.s * p.sigma;
  }
  return 0.5 * std::abs(twice);
}

/// Below this in barycentric terms a surface grazes a tetrahedron rather than cuts it.
constexpr double graze = 1e-9;

Eigen::AlignedBox3d box_of(const SweptStrip& p) {
  Eigen::AlignedBox3d b(p.origin);
  b.extend(p.origin + p.edge).extend(p.origin + p.move).extend(p.origin + p.edge + p.move);
  return b;
}

/// The least sigma at which the parallelogram's part inside the tetrahedron starts, or none (NaN).
double first_reach(const SweptStrip& p, const mesh::TetMesh& mesh, const mesh::Tet& tet) {
  const Vec3 x0 = mesh.node(tet[0]);
  Mat3 J;
  for (std::size_t k = 0; k < 3; ++k) J.col(static_cast<Index>(k)) = mesh.node(tet[k + 1]) - x0;
  const Mat3 inverse = J.inverse();
  // lambda_1..3 = inverse (X - x0), lambda_0 = 1 - their sum: each affine in (s, sigma).
  const Vec3 c = inverse * (p.origin - x0), e = inverse * p.edge, f = inverse * p.move;
  std::array<AffineCoordinate, 4> lambda{AffineCoordinate{1 - c.sum(), -e.sum(), -f.sum()}, AffineCoordinate{c.x(), e.x(), f.x()},
                                         AffineCoordinate{c.y(), e.y(), f.y()}, AffineCoordinate{c.z(), e.z(), f.z()}};
  const Polygon square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  // Whether it cuts: the part at least `graze` inside, and not a sliver (a surface through an edge
  // or a vertex). When: the least sigma of the whole part inside, so that the time is exact.
  Polygon inner = square, part = square;
  for (const auto& l : lambda) {
    inner = clip(inner, l, graze);
    part = clip(part, l, 0.0);
    if (inner.size() < 3) return std::numeric_limits<double>::quiet_NaN();
  }
  if (area(inner) <= 1e-14) return std::numeric_limits<double>::quiet_NaN();
  double sigma = 1;
  for (const auto& q : part) sigma = std::min(sigma, q.sigma);
  return std::max(0.0, sigma);
}

}  // namespace

std::vector<double> Blade::knots() const {
  std::vector<double> t{0.0};
  for (const double k : path.kinks_after(0.0)) t.push_back(k);
  return t;
}

std::vector<SweptStrip> Blade::strips() const {
  const std::vector<double> t = knots();
  std::vector<SweptStrip> out;
  for (std::size_t j = 0; j + 1 < t.size(); ++j) {
    const Vec3 from = path.at(t[j]), to = path.at(t[j + 1]);
    out.push_back({edge_a + from, edge_b - edge_a, to - from, t[j], t[j + 1]});
  }
  return out;
}

double Blade::end() const { return start + knots().back(); }

std::string Blade::describe() const { return "cut '" + name + "'" + (where.empty() ? "" : " (" + where + ")"); }

// A degenerate sweep's "crossings" would be round-off's, not a cut's.
void refuse_a_degenerate_sweep(const Blade& blade, const mesh::TetMesh& mesh) {
  double area = 0;
  for (const SweptStrip& p : blade.strips()) area += p.edge.cross(p.move).norm();
  double edges = 0;
  for (const mesh::Tet& t : mesh.tets)
    for (std::size_t a = 0; a < 4; ++a)
      for (std::size_t b = a + 1; b < 4; ++b) edges += (mesh.node(t[a]) - mesh.node(t[b])).norm();
  const double mean_edge = edges / (6.0 * static_cast<double>(std::max<std::size_t>(mesh.tets.size(), 1)));
  const double floor = smallest_swept_area * mean_edge * mean_edge;
  if (area >= floor) return;
  throw InputError(
      format("%s: the blade's edge sweeps %.3g mm^2, below %g of the mesh's mean edge squared (%.3g mm^2): "
             "an edge of no length or one moving along itself cuts nothing cleanly; give the edge a "
             "length across its motion",
             blade.describe().c_str(), area / (mm * mm), smallest_swept_area, mean_edge * mean_edge / (mm * mm)));
}

std::vector<Crossing> swept_elements(const Blade& blade, const mesh::TetMesh& mesh) {
  if (mesh.is_quadratic())
    throw InputError(mesh.source + ": " + blade.describe() + ": cuts are built for 4-node tetrahedra only");
  refuse_a_degenerate_sweep(blade, mesh);
  std::vector<double> reached(static_cast<std::size_t>(mesh.num_tets()), std::numeric_limits<double>::infinity());
  for (const SweptStrip& p : blade.strips()) {
    const Eigen::AlignedBox3d box = box_of(p);
    for (Index e = 0; e < mesh.num_tets(); ++e) {
      const mesh::Tet& tet = mesh.tets[static_cast<std::size_t>(e)];
      Eigen::AlignedBox3d tet_box(mesh.node(tet[0]));
      for (int k = 1; k < 4; ++k) tet_box.extend(mesh.node(tet[static_cast<std::size_t>(k)]));
      if (!box.intersects(tet_box)) continue;
      const double sigma = first_reach(p, mesh, tet);
      if (!(sigma >= 0)) continue;
      double& t = reached[static_cast<std::size_t>(e)];
      t = std::min(t, blade.start + p.t0 + sigma * (p.t1 - p.t0));
    }
  }
  std::vector<Crossing> crossings;
  for (Index e = 0; e < mesh.num_tets(); ++e)
    if (const double t = reached[static_cast<std::size_t>(e)]; t < std::numeric_limits<double>::infinity())
      crossings.push_back({e, t});
  std::stable_sort(crossings.begin(), crossings.end(), [](const Crossing& x, const Crossing& y) { return x.time < y.time; });
  return crossings;
}

}  // namespace roifem::cutting
