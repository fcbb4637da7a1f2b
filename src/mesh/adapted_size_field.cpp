// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/adapted_size_field.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::mesh {

namespace {

/// Lowers sizes until |s_i - s_j| <= gradation |x_i - x_j| on every edge (sweeps to a fixed point).
void limit_gradation(const TetMesh& mesh, double gradation, Vector& size) {
  const auto edges = unique_edges(mesh);
  std::vector<double> length(edges.size());
  for (std::size_t k = 0; k < edges.size(); ++k) length[k] = (mesh.node(edges[k].first) - mesh.node(edges[k].second)).norm();
  for (int sweep = 0; sweep < 200; ++sweep) {
    bool changed = false;
    for (std::size_t k = 0; k < edges.size(); ++k) {
      double& a = size[edges[k].first];
      double& b = size[edges[k].second];
      const double step = gradation * length[k];
      if (a > b + step) {
        a = b + step;
        changed = true;
      } else if (b > a + step) {
        b = a + step;
        changed = true;
      }
    }
    if (!changed) return;
  }
}

}  // namespace

AdaptedSizeField::AdaptedSizeField(TetMesh mesh, const Vector& element_error2, const SizeAdaptation& o)
    : mesh_(std::make_shared<const TetMesh>(std::move(mesh))) {
  const TetMesh& m = *mesh_;
  if (element_error2.size() != m.num_tets())
    throw InputError("adapted sizes: " + std::to_string(element_error2.size()) + " error values for " +
                     std::to_string(m.num_tets()) + " tetrahedra of " + m.source);
  for (Index e = 0; e < m.num_tets(); ++e)
    if (!(element_error2[e] >= 0) || !std::isfinite(element_error2[e]))
      throw InputError("adapted sizes: tetrahedron " + std::to_string(e) + " of " + m.source + " has error " +
                       number_text(element_error2[e]) + " (must be finite and non-negative)");
  if (!(o.order > 0 && o.max_refinement >= 1 && o.max_coarsening >= 1 && o.gradation > 0))
    throw InputError("adapted sizes: order, gradation must be positive and the per-pass bounds at least 1");

  // Per element: the size that equidistributes the error, relative to the mean error's.
  const double mean_error2 = element_error2.mean();
  const double exponent = -1.0 / (2 * o.order + 3);
  const Index N = m.num_nodes();
  Vector log_size = Vector::Zero(N), weight = Vector::Zero(N);
  for (Index e = 0; e < m.num_tets(); ++e) {
    const double volume = std::abs(signed_volume(m, e));
    const double h = std::cbrt(6 * std::numbers::sqrt2 * volume);  // a regular tetrahedron's edge
    double ratio = mean_error2 > 0 ? std::pow(element_error2[e] / mean_error2, exponent) : 1.0;
    ratio = std::clamp(ratio, 1 / o.max_refinement, o.max_coarsening);  // pow(0, -x) = inf: clamped
    for (const int a : m.tets[static_cast<std::size_t>(e)]) {
      log_size[a] += volume * std::log(h * ratio);
      weight[a] += volume;
    }
  }
  nodal_size_.resize(N);
  for (Index a = 0; a < N; ++a) nodal_size_[a] = weight[a] > 0 ? std::exp(log_size[a] / weight[a]) : 0;
  const double unused = nodal_size_.maxCoeff();
  for (Index a = 0; a < N; ++a)
    if (weight[a] == 0) nodal_size_[a] = unused;  // a node of no tetrahedron: never interpolated
  limit_gradation(m, o.gradation, nodal_size_);

  // Scale: int s^-3 dV = V (each element's mean of s^-3 over its nodes).
  double integral = 0, volume = 0;
  for (Index e = 0; e < m.num_tets(); ++e) {
    const double v = std::abs(signed_volume(m, e));
    double density = 0;
    for (const int a : m.tets[static_cast<std::size_t>(e)]) density += std::pow(nodal_size_[a], -3.0) / 4;
    integral += v * density;
    volume += v;
  }
  uniform_size_ = std::cbrt(volume / integral);
  nodal_size_ /= uniform_size_;
  locator_ = std::make_shared<const PointLocator>(*mesh_);
}

double AdaptedSizeField::relative_size(const Vec3& x) const {
  const PointLocation at = locator_->locate(x);
  double s = 0;
  for (int k = 0; k < 4; ++k) s += at.weights[static_cast<std::size_t>(k)] * nodal_size_[at.nodes[static_cast<std::size_t>(k)]];
  return s;
}

}  // namespace roifem::mesh
