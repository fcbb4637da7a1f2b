// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/assembly.hpp"

#include <algorithm>

#include "common/huge_pages.hpp"
#include "fem/tet10.hpp"
#include "fem/tet4.hpp"

namespace roifem::fem {

namespace {
std::size_t u(Index i) { return static_cast<std::size_t>(i); }
}  // namespace

StiffnessAssembler::StiffnessAssembler(const mesh::TetMesh& mesh, const DofMap& dofs)
    : mesh_(mesh), dofs_(dofs), nodes_per_tet_(mesh.is_quadratic() ? 10 : 4) {
  const Index n = mesh.num_nodes();
  element_nodes_.reserve(mesh.tets.size() * u(nodes_per_tet_));
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    element_nodes_.insert(element_nodes_.end(), mesh.tets[e].begin(), mesh.tets[e].end());
    if (mesh.is_quadratic())
      element_nodes_.insert(element_nodes_.end(), mesh.midside.of_tet[e].begin(), mesh.midside.of_tet[e].end());
  }
  // Node -> tetrahedra incidence.
  std::vector<int>& tet_start = tet_start_;
  std::vector<int>& tet_list = tet_list_;
  tet_start.assign(u(n) + 1, 0);
  tet_list.resize(element_nodes_.size());
  for (int a : element_nodes_) ++tet_start[u(a) + 1];
  for (Index i = 0; i < n; ++i) tet_start[u(i) + 1] += tet_start[u(i)];
  {
    std::vector<int> fill(tet_start.begin(), tet_start.end() - 1);
    for (std::size_t e = 0; e < mesh.tets.size(); ++e)
      for (int a : nodes_of(static_cast<Index>(e))) tet_list[u(fill[u(a)]++)] = static_cast<int>(e);
  }
  // Node graph: the nodes sharing a tetrahedron with node b, sorted, b included.
  std::vector<int> marker(u(n), -1);
  adjacency_start_.assign(u(n) + 1, 0);
  adjacency_.reserve(u(n) * 16);
  for (Index b = 0; b < n; ++b) {
    const std::size_t begin = adjacency_.size();
    for (int k = tet_start[u(b)]; k < tet_start[u(b) + 1]; ++k)
      for (int a : nodes_of(tet_list[u(k)]))
        if (marker[u(a)] != b) {
          marker[u(a)] = static_cast<int>(b);
          adjacency_.push_back(a);
        }
    std::sort(adjacency_.begin() + static_cast<std::ptrdiff_t>(begin), adjacency_.end());
    adjacency_start_[u(b) + 1] = static_cast<int>(adjacency_.size());
  }
  // Free components per node, then the rows of each column: every free component of every
  // neighbour, in node order (the free numbering is node-major, so the rows come out sorted).
  auto free_components = [&](int node) {
    return (dofs.free_dof(node, 0) >= 0) + (dofs.free_dof(node, 1) >= 0) + (dofs.free_dof(node, 2) >= 0);
  };
  adjacency_offset_.resize(adjacency_.size());
  std::vector<int> rows_of_node(u(n), 0);
  for (Index b = 0; b < n; ++b) {
    int count = 0;
    for (int k = adjacency_start_[u(b)]; k < adjacency_start_[u(b) + 1]; ++k) {
      adjacency_offset_[u(k)] = count;
      count += free_components(adjacency_[u(k)]);
    }
    rows_of_node[u(b)] = count;
  }
  column_start_.assign(u(dofs.num_free()) + 1, 0);
  for (Index j = 0; j < dofs.num_free(); ++j)
    column_start_[u(j) + 1] = column_start_[u(j)] + rows_of_node[u(dofs.full_dof(j) / 3)];
  row_index_.resize(u(column_start_.back()));
  for (Index j = 0; j < dofs.num_free(); ++j) {
    const Index b = dofs.full_dof(j) / 3;
    int pos = column_start_[u(j)];
    for (int k = adjacency_start_[u(b)]; k < adjacency_start_[u(b) + 1]; ++k)
      for (int c = 0; c < 3; ++c)
        if (const int row = dofs.free_dof(adjacency_[u(k)], c); row >= 0) row_index_[u(pos++)] = row;
  }
}

SparseMatrix StiffnessAssembler::stiffness(const MaterialMap& materials) const {
  const Index n_free = dofs_.num_free();
  SparseMatrix K(n_free, n_free);
  K.resizeNonZeros(static_cast<Index>(row_index_.size()));  // uninitialised: each column fills its own below
  std::copy(column_start_.begin(), column_start_.end(), K.outerIndexPtr());
  int* rows = K.innerIndexPtr();
  double* values = K.valuePtr();
  advise_huge_pages(values, row_index_.size() * sizeof(double));
  advise_huge_pages(rows, row_index_.size() * sizeof(int));

  const Index n_nodes = mesh_.num_nodes();
  // Nodes whose three components are all free (the common case) take a branch-free path.
  std::vector<char> all_free(u(n_nodes));
  for (Index n = 0; n < n_nodes; ++n)
    all_free[u(n)] = dofs_.free_dof(n, 0) >= 0 && dofs_.free_dof(n, 1) >= 0 && dofs_.free_dof(n, 2) >= 0;
#pragma omp parallel for schedule(dynamic, 64)
  for (Index b = 0; b < n_nodes; ++b) {
    int column[3] = {-1, -1, -1};
    bool any_free = false;
    for (int cb = 0; cb < 3; ++cb) any_free |= (column[cb] = dofs_.free_dof(b, cb)) >= 0;
    if (!any_free) continue;
    // First touch of this node's columns happens here, on this thread: copy the row indices and
    // zero the values (a separate memset of the array cost as much as the assembly:
    // docs/design-figures.md).
    for (int cb = 0; cb < 3; ++cb)
      if (column[cb] >= 0) {
        const int begin = column_start_[u(column[cb])], end = column_start_[u(column[cb]) + 1];
        std::copy(row_index_.begin() + begin, row_index_.begin() + end, rows + begin);
        std::fill(values + begin, values + end, 0.0);
      }
    const int* adj_begin = adjacency_.data() + adjacency_start_[u(b)];
    const int* adj_end = adjacency_.data() + adjacency_start_[u(b) + 1];
    // Adds block K_ab (rows: node a's components, columns: b's) into b's columns.
    auto add_block = [&](int node_a, const Mat3& K_ab) {
      const int offset = adjacency_offset_[u(std::lower_bound(adj_begin, adj_end, node_a) - adjacency_.data())];
      if (all_free[u(node_a)] && all_free[u(b)]) {
        for (int cb = 0; cb < 3; ++cb) {
          double* target = values + column_start_[u(column[cb])] + offset;
          target[0] += K_ab(0, cb);
          target[1] += K_ab(1, cb);
          target[2] += K_ab(2, cb);
        }
        return;
      }
      for (int cb = 0; cb < 3; ++cb) {
        if (column[cb] < 0) continue;
        double* target = values + column_start_[u(column[cb])] + offset;
        for (int ca = 0, local = 0; ca < 3; ++ca)
          if (dofs_.free_dof(node_a, ca) >= 0) target[local++] += K_ab(ca, cb);
      }
    };
    for (int k = tet_start_[u(b)]; k < tet_start_[u(b) + 1]; ++k) {
      const int e = tet_list_[u(k)];
      const auto& t = mesh_.tets[u(e)];  // the corners
      const Material& material = materials.of(e);
      if (nodes_per_tet_ == tet10_nodes) {
        const auto nodes = nodes_of(e);
        const int local_b = static_cast<int>(std::find(nodes.begin(), nodes.end(), static_cast<int>(b)) - nodes.begin());
        const Tet10Geometry g = tet10_geometry(mesh_.node(t[0]), mesh_.node(t[1]), mesh_.node(t[2]), mesh_.node(t[3]));
        for (int a = 0; a < tet10_nodes; ++a) add_block(nodes[u(a)], tet10_stiffness_block(g, material, a, local_b));
        continue;
      }
      const int local_b = static_cast<int>(std::find(t.begin(), t.end(), static_cast<int>(b)) - t.begin());
      const Tet4Geometry g = tet4_geometry(mesh_.node(t[0]), mesh_.node(t[1]), mesh_.node(t[2]), mesh_.node(t[3]));
      for (int a = 0; a < 4; ++a) add_block(t[u(a)], tet4_stiffness_block(g, material, a, local_b));
    }
  }
  return K;
}

Vector StiffnessAssembler::prescribed_load(const MaterialMap& materials) const {
  Vector load = Vector::Zero(dofs_.num_free());
  const Vector& up = dofs_.prescribed();
  for (Index e = 0; e < mesh_.num_tets(); ++e) {
    const auto t = nodes_of(e);
    if (std::all_of(t.begin(), t.end(), [&](int n) { return up.segment<3>(3 * n).isZero(0.0); })) continue;
    const auto& c = mesh_.tets[u(e)];
    Vector ue(3 * nodes_per_tet_);
    for (int a = 0; a < nodes_per_tet_; ++a) ue.segment<3>(3 * a) = up.segment<3>(3 * t[u(a)]);
    const Vector fe =
        nodes_per_tet_ == tet10_nodes
            ? Vector(tet10_stiffness(tet10_geometry(mesh_.node(c[0]), mesh_.node(c[1]), mesh_.node(c[2]), mesh_.node(c[3])),
                                     materials.of(e)) *
                     ue)
            : Vector(tet4_stiffness(tet4_geometry(mesh_.node(c[0]), mesh_.node(c[1]), mesh_.node(c[2]), mesh_.node(c[3])),
                                    materials.of(e)) *
                     ue);
    for (int a = 0; a < nodes_per_tet_; ++a)
      for (int k = 0; k < 3; ++k)
        if (const int i = dofs_.free_dof(t[u(a)], k); i >= 0) load[i] -= fe[3 * a + k];
  }
  return load;
}

Vector lumped_node_mass(const mesh::TetMesh& mesh, double rho) {
  return lumped_node_mass(mesh, MaterialMap(Material{0, 0, rho, 0}));
}

Vector lumped_node_mass(const mesh::TetMesh& mesh, const MaterialMap& materials) {
  Vector m = Vector::Zero(mesh.num_nodes());
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const double mass = materials.of(e).rho * std::abs(mesh::signed_volume(mesh, e));
    if (mesh.is_quadratic()) {
      for (int a : mesh.tets[u(e)]) m[a] += tet10_corner_mass * mass;
      for (int a : mesh.midside.of_tet[u(e)]) m[a] += tet10_midside_mass * mass;
      continue;
    }
    const double quarter = mass / 4.0;
    for (int a : mesh.tets[u(e)]) m[a] += quarter;
  }
  return m;
}

Vector lumped_mass(const mesh::TetMesh& mesh, const DofMap& dofs, double rho) {
  return lumped_mass(mesh, dofs, MaterialMap(Material{0, 0, rho, 0}));
}

Vector lumped_mass(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials) {
  const Vector node_mass = lumped_node_mass(mesh, materials);
  Vector m(dofs.num_free());
  for (Index i = 0; i < dofs.num_free(); ++i) m[i] = node_mass[dofs.full_dof(i) / 3];
  return m;
}

}  // namespace roifem::fem
