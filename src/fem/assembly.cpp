#include "fem/assembly.hpp"

#include <algorithm>
#include <numeric>

#include "fem/tet4.hpp"

namespace roifem::fem {

namespace {
std::size_t u(Index i) { return static_cast<std::size_t>(i); }
}  // namespace

StiffnessAssembler::StiffnessAssembler(const mesh::TetMesh& mesh, const DofMap& dofs) : mesh_(mesh), dofs_(dofs) {
  const Index n = mesh.num_nodes();
  // Node -> tetrahedra incidence.
  std::vector<int> tet_start(u(n) + 1, 0), tet_list(mesh.tets.size() * 4);
  for (const auto& t : mesh.tets)
    for (int a : t) ++tet_start[u(a) + 1];
  for (Index i = 0; i < n; ++i) tet_start[u(i) + 1] += tet_start[u(i)];
  {
    std::vector<int> fill(tet_start.begin(), tet_start.end() - 1);
    for (std::size_t e = 0; e < mesh.tets.size(); ++e)
      for (int a : mesh.tets[e]) tet_list[u(fill[u(a)]++)] = static_cast<int>(e);
  }
  // Node graph: the nodes sharing a tetrahedron with node b, sorted, b included.
  std::vector<int> marker(u(n), -1);
  adjacency_start_.assign(u(n) + 1, 0);
  adjacency_.reserve(u(n) * 16);
  for (Index b = 0; b < n; ++b) {
    const std::size_t begin = adjacency_.size();
    for (int k = tet_start[u(b)]; k < tet_start[u(b) + 1]; ++k)
      for (int a : mesh.tets[u(tet_list[u(k)])])
        if (marker[u(a)] != b) {
          marker[u(a)] = static_cast<int>(b);
          adjacency_.push_back(a);
        }
    std::sort(adjacency_.begin() + static_cast<std::ptrdiff_t>(begin), adjacency_.end());
    adjacency_start_[u(b) + 1] = static_cast<int>(adjacency_.size());
  }
  // Visit tetrahedra in the order of their lowest node, so that consecutive elements write into
  // nearby columns (the values array of a 100k-node brain is 100 MB: scattered writes miss cache).
  element_order_.resize(mesh.tets.size());
  std::iota(element_order_.begin(), element_order_.end(), 0);
  std::vector<int> lowest(mesh.tets.size());
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) lowest[e] = *std::min_element(mesh.tets[e].begin(), mesh.tets[e].end());
  std::stable_sort(element_order_.begin(), element_order_.end(),
                   [&](int a, int b) { return lowest[u(a)] < lowest[u(b)]; });
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

SparseMatrix StiffnessAssembler::stiffness(const Material& material) const {
  const Index n_free = dofs_.num_free();
  SparseMatrix K(n_free, n_free);
  K.resizeNonZeros(static_cast<Index>(row_index_.size()));
  std::copy(column_start_.begin(), column_start_.end(), K.outerIndexPtr());
  std::copy(row_index_.begin(), row_index_.end(), K.innerIndexPtr());
  double* values = K.valuePtr();
  std::fill(values, values + row_index_.size(), 0.0);

  for (const int e : element_order_) {
    const auto& t = mesh_.tets[u(e)];
    const Tet4Geometry g = tet4_geometry(mesh_.node(t[0]), mesh_.node(t[1]), mesh_.node(t[2]), mesh_.node(t[3]));
    const ElementMatrix Ke = tet4_stiffness(g, material);
    for (int b = 0; b < 4; ++b) {
      const int node_b = t[u(b)];
      const int* adj_begin = adjacency_.data() + adjacency_start_[u(node_b)];
      const int* adj_end = adjacency_.data() + adjacency_start_[u(node_b) + 1];
      int offset[4];  // where node a's rows start within node b's columns
      for (int a = 0; a < 4; ++a)
        offset[a] = adjacency_offset_[u(std::lower_bound(adj_begin, adj_end, t[u(a)]) - adjacency_.data())];
      for (int cb = 0; cb < 3; ++cb) {
        const int col = dofs_.free_dof(node_b, cb);
        if (col < 0) continue;
        double* column = values + column_start_[u(col)];
        for (int a = 0; a < 4; ++a) {
          int local = offset[a];
          for (int ca = 0; ca < 3; ++ca)
            if (dofs_.free_dof(t[u(a)], ca) >= 0) column[local++] += Ke(3 * a + ca, 3 * b + cb);
        }
      }
    }
  }
  return K;
}

Vector StiffnessAssembler::prescribed_load(const Material& material) const {
  Vector load = Vector::Zero(dofs_.num_free());
  const Vector& up = dofs_.prescribed();
  for (const auto& t : mesh_.tets) {
    Eigen::Matrix<double, 12, 1> ue;
    for (int a = 0; a < 4; ++a) ue.segment<3>(3 * a) = up.segment<3>(3 * t[u(a)]);
    if (ue.isZero(0.0)) continue;
    const Tet4Geometry g = tet4_geometry(mesh_.node(t[0]), mesh_.node(t[1]), mesh_.node(t[2]), mesh_.node(t[3]));
    const Eigen::Matrix<double, 12, 1> fe = tet4_stiffness(g, material) * ue;
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 3; ++c)
        if (const int i = dofs_.free_dof(t[u(a)], c); i >= 0) load[i] -= fe[3 * a + c];
  }
  return load;
}

Vector lumped_node_mass(const mesh::TetMesh& mesh, double rho) {
  Vector m = Vector::Zero(mesh.num_nodes());
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const double quarter = rho * std::abs(mesh::signed_volume(mesh, e)) / 4.0;
    for (int a : mesh.tets[u(e)]) m[a] += quarter;
  }
  return m;
}

Vector lumped_mass(const mesh::TetMesh& mesh, const DofMap& dofs, double rho) {
  const Vector node_mass = lumped_node_mass(mesh, rho);
  Vector m(dofs.num_free());
  for (Index i = 0; i < dofs.num_free(); ++i) m[i] = node_mass[dofs.full_dof(i) / 3];
  return m;
}

}  // namespace roifem::fem
