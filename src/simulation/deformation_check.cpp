// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/deformation_check.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "common/format.hpp"

namespace roifem::simulation {

void PeakDisplacement::observe(long step, const model::State& s) {
  double largest = 0;
  for (const auto& node : nodes_) {
    double squared = 0;
    for (const Index i : node)
      if (i >= 0) squared += s.u[i] * s.u[i];
    largest = std::max(largest, squared);
  }
  for (const auto& tool : tools_->tools()) largest = std::max(largest, tool.path.at(s.t).squaredNorm());
  if (std::sqrt(largest) > peak_) {
    peak_ = std::sqrt(largest);
    step_ = step;
    state_ = s;
  }
}

namespace {

double mean_edge_length(const mesh::TetMesh& mesh) {
  double sum = 0;
  for (const auto& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) sum += (mesh.node(t[a]) - mesh.node(t[b])).norm();
  return mesh.tets.empty() ? 0 : sum / (6.0 * static_cast<double>(mesh.tets.size()));
}

}  // namespace

DeformationReport check_deformation(ScenarioModel& model, const PeakDisplacement& peak, const std::vector<bool>& still_there,
                                    const std::vector<mesh::Tet>* tets_at_peak) {
  DeformationReport r;
  const mesh::TetMesh& mesh = model.mesh;
  const Vec3 extent = mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff();
  r.smallest_extent_m = extent.minCoeff();
  r.mean_edge_m = mean_edge_length(mesh);
  if (peak.state().u.size() == 0) return r;
  const model::State& s = peak.state();
  const Vector u_free = model.condensation ? model.condensation->expand(s.u, s.t) : s.u;
  const Vector u = model.full.displacement(u_free, s.t);  // 3 per node, the tools' nodes on their paths
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    const double d = u.segment<3>(3 * static_cast<Index>(n)).norm();
    if (d > r.peak_m) {
      r.peak_m = d;
      r.peak_node = n;
    }
  }
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    if (!still_there.empty() && !still_there[static_cast<std::size_t>(e)]) continue;
    const auto& t = (tets_at_peak ? *tets_at_peak : mesh.tets)[static_cast<std::size_t>(e)];
    auto x = [&](int a) -> Vec3 { return mesh.node(t[a]) + u.segment<3>(3 * static_cast<Index>(t[a])); };
    const Vec3 p0 = x(0);
    if ((x(1) - p0).cross(x(2) - p0).dot(x(3) - p0) <= 0) {
      if (r.inverted++ == 0) r.first_inverted = e;
    }
  }
  // A neo-Hookean model is made for large deformations: the size warnings are the linear law's.
  const bool linear = !model.full.system.is_nonlinear();
  if (linear && r.peak_m > 0.1 * r.smallest_extent_m)
    r.warnings.push_back(
        format("the peak displacement %.3g mm exceeds a tenth of the mesh's smallest extent (%.3g mm): "
               "far beyond small deformations, where a linear model means little (check the forces' "
               "size and units: N)",
               r.peak_m / mm, r.smallest_extent_m / mm));
  else if (linear && r.peak_m > 3 * r.mean_edge_m)
    r.warnings.push_back(format("the peak displacement %.3g mm exceeds three mean element edges (%.3g mm each)", r.peak_m / mm,
                                r.mean_edge_m / mm));
  if (r.inverted > 0)
    r.warnings.push_back(
        format("the %s solution turns %lld tetrahedra inside out (the first: element %lld), "
               "physically impossible",
               linear ? "linear" : "nonlinear", static_cast<long long>(r.inverted), static_cast<long long>(r.first_inverted)));
  return r;
}

}  // namespace roifem::simulation
