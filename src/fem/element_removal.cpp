// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/element_removal.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "fem/tet4.hpp"

namespace roifem::fem {

namespace {

/// InputError unless `removed` are distinct tetrahedra of the mesh, all still there.
void check_removable(const mesh::TetMesh& mesh, const std::vector<bool>& alive, const std::vector<Index>& removed) {
  if (mesh.is_quadratic()) throw InputError("removing elements: only a linear (4-node) mesh is taken so far");
  std::vector<Index> sorted = removed;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    const Index e = sorted[k];
    if (e < 0 || e >= mesh.num_tets())
      throw InputError("removing elements: tetrahedron " + std::to_string(e) + " is not in the mesh");
    if (!alive[static_cast<std::size_t>(e)] || (k > 0 && sorted[k - 1] == e))
      throw InputError("removing elements: tetrahedron " + std::to_string(e) + " is removed twice");
  }
}

/// The change; `elements_at` (per node, the tetrahedra holding it before) is decremented.
ElementRemoval removal_change(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials,
                              const std::vector<Index>& removed, double c, std::vector<int>& elements_at) {
  for (const Index e : removed)
    for (const int n : mesh.tets[static_cast<std::size_t>(e)]) --elements_at[static_cast<std::size_t>(n)];
  ElementRemoval r;
  for (const Index e : removed)
    for (const int n : mesh.tets[static_cast<std::size_t>(e)])
      for (int i = 0; i < 3; ++i)
        if (const int d = dofs.free_dof(n, i); d >= 0) r.dofs.push_back(d);
  std::sort(r.dofs.begin(), r.dofs.end());
  r.dofs.erase(std::unique(r.dofs.begin(), r.dofs.end()), r.dofs.end());
  auto local = [&](int d) {
    return static_cast<Index>(std::lower_bound(r.dofs.begin(), r.dofs.end(), Index{d}) - r.dofs.begin());
  };
  const auto size = static_cast<Index>(r.dofs.size());
  r.change = DenseMatrix::Zero(size, size);
  r.mass_change = Vector::Zero(size);
  Vector orphan_mass = Vector::Zero(size);  // c m_i of an orphan's dofs, their pins
  for (const Index e : removed) {
    const auto& nodes = mesh.tets[static_cast<std::size_t>(e)];
    const Tet4Geometry g = tet4_geometry(mesh.node(nodes[0]), mesh.node(nodes[1]), mesh.node(nodes[2]), mesh.node(nodes[3]));
    const Material& m = materials.of(e);
    const ElementMatrix K = tet4_stiffness(g, m);
    const double quarter = m.rho * std::abs(g.volume) / 4;
    int row[12];
    for (int k = 0; k < 12; ++k) row[k] = dofs.free_dof(nodes[static_cast<std::size_t>(k / 3)], k % 3);
    for (int a = 0; a < 12; ++a) {
      if (row[a] < 0) continue;
      const Index i = local(row[a]);
      for (int b = 0; b < 12; ++b)
        if (row[b] >= 0) r.change(i, local(row[b])) -= K(a, b);
      r.change(i, i) -= c * quarter;
      r.mass_change[i] -= quarter;
      if (elements_at[static_cast<std::size_t>(nodes[static_cast<std::size_t>(a / 3)])] == 0) orphan_mass[i] += c * quarter;
    }
  }
  for (Index i = 0; i < size; ++i) r.change(i, i) += orphan_mass[i];
  for (const Index e : removed)
    for (const int n : mesh.tets[static_cast<std::size_t>(e)])
      if (elements_at[static_cast<std::size_t>(n)] == 0) r.orphan_nodes.push_back(n);
  std::sort(r.orphan_nodes.begin(), r.orphan_nodes.end());
  r.orphan_nodes.erase(std::unique(r.orphan_nodes.begin(), r.orphan_nodes.end()), r.orphan_nodes.end());
  return r;
}

std::vector<int> elements_at_nodes(const mesh::TetMesh& mesh, const std::vector<bool>& alive) {
  std::vector<int> count(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (std::size_t e = 0; e < alive.size(); ++e)
    if (alive[e])
      for (const int n : mesh.tets[e]) ++count[static_cast<std::size_t>(n)];
  return count;
}

}  // namespace

ElementRemoval element_removal(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials,
                               const std::vector<Index>& removed, double c, const std::vector<bool>& still_there) {
  const auto elements = static_cast<std::size_t>(mesh.num_tets());
  const std::vector<bool> alive = still_there.empty() ? std::vector<bool>(elements, true) : still_there;
  if (alive.size() != elements) throw Error("internal: removing elements: the alive mask does not match the mesh");
  check_removable(mesh, alive, removed);
  std::vector<int> count = elements_at_nodes(mesh, alive);
  return removal_change(mesh, dofs, materials, removed, c, count);
}

ElementRemover::ElementRemover(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials)
    : mesh_(&mesh),
      dofs_(&dofs),
      materials_(&materials),
      alive_(static_cast<std::size_t>(mesh.num_tets()), true),
      elements_at_(elements_at_nodes(mesh, alive_)) {}

ElementRemoval ElementRemover::remove(const std::vector<Index>& removed, double c) {
  check_removable(*mesh_, alive_, removed);
  ElementRemoval r = removal_change(*mesh_, *dofs_, *materials_, removed, c, elements_at_);
  for (const Index e : removed) alive_[static_cast<std::size_t>(e)] = false;
  return r;
}

}  // namespace roifem::fem
