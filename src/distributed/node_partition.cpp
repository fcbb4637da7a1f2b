// SPDX-License-Identifier: GPL-3.0-or-later
#include "distributed/node_partition.hpp"

#include <algorithm>
#include <numeric>

#include "common/errors.hpp"
#include "distributed/petsc_handle.hpp"

namespace roifem::distributed {

std::vector<int> element_nodes(const mesh::TetMesh& mesh, Index e) {
  const auto& t = mesh.tets[static_cast<std::size_t>(e)];
  std::vector<int> nodes(t.begin(), t.end());
  if (mesh.is_quadratic()) {
    const auto& mid = mesh.midside.of_tet[static_cast<std::size_t>(e)];
    nodes.insert(nodes.end(), mid.begin(), mid.end());
  }
  return nodes;
}

NodeGraph NodeGraph::of(const mesh::TetMesh& mesh) {
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  const std::size_t per_tet = mesh.is_quadratic() ? 10 : 4;
  std::vector<int> flat;  // each tetrahedron's nodes, per_tet apiece
  flat.reserve(mesh.tets.size() * per_tet);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const std::vector<int> nodes = element_nodes(mesh, static_cast<Index>(e));
    flat.insert(flat.end(), nodes.begin(), nodes.end());
  }
  std::vector<PetscInt> tet_start(n + 1, 0);  // node -> tetrahedra (CSR)
  for (const int a : flat) ++tet_start[static_cast<std::size_t>(a) + 1];
  std::partial_sum(tet_start.begin(), tet_start.end(), tet_start.begin());
  std::vector<PetscInt> tets_of(static_cast<std::size_t>(tet_start.back()));
  std::vector<PetscInt> fill(tet_start.begin(), tet_start.end() - 1);
  for (std::size_t k = 0; k < flat.size(); ++k)
    tets_of[static_cast<std::size_t>(fill[static_cast<std::size_t>(flat[k])]++)] = static_cast<PetscInt>(k / per_tet);
  NodeGraph g;
  g.start.assign(n + 1, 0);
  std::vector<PetscInt> row;
  for (std::size_t a = 0; a < n; ++a) {
    row.clear();
    for (PetscInt k = tet_start[a]; k < tet_start[a + 1]; ++k) {
      const std::size_t e = static_cast<std::size_t>(tets_of[static_cast<std::size_t>(k)]);
      for (std::size_t i = 0; i < per_tet; ++i)
        if (const int b = flat[e * per_tet + i]; static_cast<std::size_t>(b) != a) row.push_back(b);
    }
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    g.neighbours.insert(g.neighbours.end(), row.begin(), row.end());
    g.start[a + 1] = static_cast<PetscInt>(g.neighbours.size());
  }
  return g;
}

int NodePartition::owner(PetscInt k) const {
  return static_cast<int>(std::upper_bound(first.begin(), first.end(), k) - first.begin()) - 1;
}

namespace {

/// The free nodes in mesh order; InputError at the first node with some but not all dofs fixed.
std::vector<int> whole_free_nodes(const mesh::TetMesh& mesh, const fem::DofMap& dofs) {
  std::vector<int> free;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    int count = 0;
    for (int c = 0; c < 3; ++c) count += dofs.free_dof(n, c) >= 0 ? 1 : 0;
    if (count == 3) free.push_back(n);
    if (count == 1 || count == 2)
      throw InputError(mesh.source + ": node " + std::to_string(n) +
                       " has only some components fixed; the distributed model fixes whole nodes (block size 3)");
  }
  return free;
}

}  // namespace

NodePartition partition_free_nodes(const mesh::TetMesh& mesh, const fem::DofMap& dofs, const NodeGraph& graph, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const std::vector<int> free = whole_free_nodes(mesh, dofs);
  const auto count = static_cast<PetscInt>(free.size());
  NodePartition p;
  p.rank = rank;
  p.number.assign(static_cast<std::size_t>(mesh.num_nodes()), -1);
  // The first deal, in mesh order: rank r holds [count r / size, count (r + 1) / size).
  auto block = [&](int r) { return static_cast<PetscInt>(static_cast<long long>(count) * r / size); };
  std::vector<PetscInt> order(free.size());  // order[k]: the final number of free node k
  std::iota(order.begin(), order.end(), 0);
  p.first.resize(static_cast<std::size_t>(size) + 1);
  for (int r = 0; r <= size; ++r) p.first[static_cast<std::size_t>(r)] = block(r);
  if (size > 1) {
    std::vector<PetscInt> index_of(static_cast<std::size_t>(mesh.num_nodes()), -1);
    for (std::size_t k = 0; k < free.size(); ++k) index_of[static_cast<std::size_t>(free[k])] = static_cast<PetscInt>(k);
    const PetscInt begin = block(rank), end = block(rank + 1);
    PetscInt* ia = nullptr;
    PetscInt* ja = nullptr;
    std::vector<PetscInt> ia_v{0}, ja_v;
    for (PetscInt k = begin; k < end; ++k) {
      const auto a = static_cast<std::size_t>(free[static_cast<std::size_t>(k)]);
      for (PetscInt j = graph.start[a]; j < graph.start[a + 1]; ++j)
        if (const PetscInt b = index_of[static_cast<std::size_t>(graph.neighbours[static_cast<std::size_t>(j)])]; b >= 0)
          ja_v.push_back(b);
      ia_v.push_back(static_cast<PetscInt>(ja_v.size()));
    }
    // MatCreateMPIAdj takes ownership of PetscMalloc'ed arrays.
    check(PetscMalloc1(ia_v.size(), &ia), "PetscMalloc1");
    check(PetscMalloc1(std::max<std::size_t>(ja_v.size(), 1), &ja), "PetscMalloc1");
    std::copy(ia_v.begin(), ia_v.end(), ia);
    std::copy(ja_v.begin(), ja_v.end(), ja);
    OwnedMat adjacency;
    check(MatCreateMPIAdj(comm, end - begin, count, ia, ja, nullptr, adjacency.out()), "MatCreateMPIAdj");
    OwnedPartitioning partitioning;
    check(MatPartitioningCreate(comm, partitioning.out()), "MatPartitioningCreate");
    check(MatPartitioningSetAdjacency(partitioning.get(), adjacency.get()), "MatPartitioningSetAdjacency");
    check(MatPartitioningSetType(partitioning.get(), MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType(ptscotch)");
    check(MatPartitioningSetFromOptions(partitioning.get()), "MatPartitioningSetFromOptions");
    OwnedIs part, numbering, all;
    check(MatPartitioningApply(partitioning.get(), part.out()), "MatPartitioningApply");
    check(ISPartitioningToNumbering(part.get(), numbering.out()), "ISPartitioningToNumbering");
    std::vector<PetscInt> counts(static_cast<std::size_t>(size));
    check(ISPartitioningCount(part.get(), size, counts.data()), "ISPartitioningCount");
    check(ISAllGather(numbering.get(), all.out()), "ISAllGather");
    const PetscInt* numbers = nullptr;
    check(ISGetIndices(all.get(), &numbers), "ISGetIndices");
    std::copy(numbers, numbers + count, order.begin());
    check(ISRestoreIndices(all.get(), &numbers), "ISRestoreIndices");
    p.first[0] = 0;
    for (int r = 0; r < size; ++r)
      p.first[static_cast<std::size_t>(r) + 1] = p.first[static_cast<std::size_t>(r)] + counts[static_cast<std::size_t>(r)];
  }
  for (std::size_t k = 0; k < free.size(); ++k) p.number[static_cast<std::size_t>(free[k])] = order[k];
  p.owned_nodes.resize(static_cast<std::size_t>(p.owned_end() - p.owned_begin()));
  for (std::size_t k = 0; k < free.size(); ++k)
    if (order[k] >= p.owned_begin() && order[k] < p.owned_end())
      p.owned_nodes[static_cast<std::size_t>(order[k] - p.owned_begin())] = free[k];
  return p;
}

}  // namespace roifem::distributed
