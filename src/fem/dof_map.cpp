// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/dof_map.hpp"

#include <cmath>

#include "common/errors.hpp"

namespace roifem::fem {

Constraints::Constraints(Index num_nodes)
    : constrained_(static_cast<std::size_t>(3 * num_nodes), false), value_(static_cast<std::size_t>(3 * num_nodes), 0.0) {}

void Constraints::prescribe(Index node, int component, double value) {
  if (node < 0 || node >= num_nodes() || component < 0 || component > 2)
    throw InputError("Dirichlet condition on node " + std::to_string(node) + ", component " + std::to_string(component) +
                     ": no such degree of freedom");
  if (!std::isfinite(value))
    throw InputError("Dirichlet condition on node " + std::to_string(node) + ": value is NaN or infinite");
  constrained_[static_cast<std::size_t>(3 * node + component)] = true;
  value_[static_cast<std::size_t>(3 * node + component)] = value;
}

void Constraints::fix_node(Index node, const Vec3& value) {
  for (int c = 0; c < 3; ++c) prescribe(node, c, value[c]);
}

void Constraints::fix_set(const mesh::TetMesh& mesh, const std::string& set_name) {
  const auto& set = mesh.set(set_name);
  if (set.nodes.empty()) throw InputError(mesh.source + ": named set '" + set_name + "' has no nodes to fix");
  for (int n : set.nodes) fix_node(n);
}

DofMap::DofMap(const Constraints& constraints) {
  const Index n_full = 3 * constraints.num_nodes();
  free_index_.assign(static_cast<std::size_t>(n_full), -1);
  prescribed_ = Vector::Zero(n_full);
  for (Index d = 0; d < n_full; ++d) {
    if (constraints.is_constrained(d)) {
      prescribed_[d] = constraints.value(d);
    } else {
      free_index_[static_cast<std::size_t>(d)] = static_cast<int>(full_index_.size());
      full_index_.push_back(d);
    }
  }
}

Vector DofMap::expand(const Eigen::Ref<const Vector>& u_free) const {
  Vector full = prescribed_;
  for (Index i = 0; i < num_free(); ++i) full[full_dof(i)] = u_free[i];
  return full;
}

Vector DofMap::expand_homogeneous(const Eigen::Ref<const Vector>& u_free) const {
  Vector full = Vector::Zero(num_full());
  for (Index i = 0; i < num_free(); ++i) full[full_dof(i)] = u_free[i];
  return full;
}

Vector DofMap::restrict_to_free(const Eigen::Ref<const Vector>& full) const {
  Vector free(num_free());
  for (Index i = 0; i < num_free(); ++i) free[i] = full[full_dof(i)];
  return free;
}

}  // namespace roifem::fem
