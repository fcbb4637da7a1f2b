// SPDX-License-Identifier: GPL-3.0-or-later
// The low-rank update of a factored matrix (solvers/low_rank_update.hpp) and the change that
// removing tetrahedra makes to the trapezoidal rule's K_eff (fem/element_removal.hpp), each against
// an independent expectation: a dense factorization of the changed matrix; CHOLMOD's factor of the
// matrix assembled from scratch on the cut mesh, after one cut and after several (one of which
// leaves a node with no element); the lumped mass of the cut mesh.
#include "solvers/low_rank_update.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "common/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/element_removal.hpp"
#include "mesh/box_mesh.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::solvers {
namespace {

/// R R^T + n I, R's entries uniform in [-1, 1]: symmetric positive definite, well conditioned.
DenseMatrix random_spd(Index n, std::mt19937& rng) {
  std::uniform_real_distribution<double> draw(-1, 1);
  DenseMatrix R(n, n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j) R(i, j) = draw(rng);
  return R * R.transpose() + static_cast<double>(n) * DenseMatrix::Identity(n, n);
}

/// changed(dofs, dofs) += B: the change a LowRankUpdate takes, made to the dense matrix.
void add_on(DenseMatrix& changed, const std::vector<Index>& dofs, const DenseMatrix& B) {
  for (std::size_t i = 0; i < dofs.size(); ++i)
    for (std::size_t j = 0; j < dofs.size(); ++j) changed(dofs[i], dofs[j]) += B(static_cast<Index>(i), static_cast<Index>(j));
}

TEST(LowRankUpdate, SolvesWithTheChangedMatrixAsADenseFactorizationOfItDoes) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> draw(-1, 1);
  const Index n = 40;
  const DenseMatrix A = random_spd(n, rng);
  const Eigen::LLT<DenseMatrix> A_factor(A);
  LowRankUpdate update([&](const Vector& b, Vector& x) { x = A_factor.solve(b); }, n);
  DenseMatrix changed = A;
  // Two changes that share dofs 7 and 30: the second adds to the first's block there.
  for (const std::vector<Index>& dofs : {std::vector<Index>{3, 7, 30}, std::vector<Index>{30, 11, 7, 25}}) {
    const auto r = static_cast<Index>(dofs.size());
    DenseMatrix S(r, r);
    for (Index i = 0; i < r; ++i)
      for (Index j = 0; j < r; ++j) S(i, j) = draw(rng);
    const DenseMatrix B = -0.5 * (S * S.transpose());  // a removal: negative semidefinite
    update.add(dofs, B);
    add_on(changed, dofs, B);
  }
  EXPECT_EQ(update.rank(), 5);
  Vector b(n), x(n);
  for (Index i = 0; i < n; ++i) b[i] = draw(rng);
  update.solve(b, x);
  const Vector expected = changed.partialPivLu().solve(b);
  EXPECT_LT((x - expected).norm(), 1e-13 * expected.norm());
  EXPECT_LT((changed * x - b).norm(), 1e-12 * b.norm());
}

TEST(LowRankUpdate, ColumnsSolvedAheadGiveTheSameSolveAndSpareTheChangeItsSolves) {
  // Many changes, one dof at a time (Z grows past its room several times), half of them with their
  // columns prefetched: the same solution as a dense factorization, and the prefetched changes call
  // no solve with A.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> draw(-1, 1);
  const Index n = 30;
  const DenseMatrix A = random_spd(n, rng);
  const Eigen::LLT<DenseMatrix> A_factor(A);
  long solves = 0;
  LowRankUpdate update(
      [&](const Vector& b, Vector& x) {
        ++solves;
        x = A_factor.solve(b);
      },
      n);
  DenseMatrix changed = A;
  for (Index d = 0; d < 12; ++d) {
    const std::vector<Index> dofs{d, d + 12};
    if (d % 2 == 0) update.prefetch(dofs);
    EXPECT_TRUE(d % 2 == 1 || (update.has_column(d) && update.has_column(d + 12)));
    const long before = solves;
    const DenseMatrix B = DenseMatrix::Constant(2, 2, -0.3 - 0.01 * static_cast<double>(d)) + DenseMatrix::Identity(2, 2);
    update.add(dofs, B);
    if (d % 2 == 0) {
      EXPECT_EQ(solves, before) << "change " << d;
    }
    add_on(changed, dofs, B);
  }
  EXPECT_EQ(update.rank(), 24);
  Vector b(n), x(n);
  for (Index i = 0; i < n; ++i) b[i] = draw(rng);
  update.solve(b, x);
  const Vector expected = changed.partialPivLu().solve(b);
  EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
}

TEST(LowRankUpdate, ABadDofIsNamedAndTheUpdateIsLeftAsItWas) {
  LowRankUpdate update([](const Vector& b, Vector& x) { x = b; }, 5);  // A = I
  update.add({2}, DenseMatrix::Constant(1, 1, 1.0));                   // A + e_2 e_2^T
  try {
    update.add({0, 1, 1}, DenseMatrix::Zero(3, 3));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dof 1 is given twice"), std::string::npos) << e.what();
  }
  EXPECT_THROW(update.add({5}, DenseMatrix::Zero(1, 1)), InputError);
  EXPECT_THROW(update.add({3}, DenseMatrix::Constant(1, 1, -1.0)), SolverError);  // row 3 zeroed: singular
  EXPECT_EQ(update.rank(), 1);
  Vector x(5);
  update.solve(Vector::Ones(5), x);
  EXPECT_LT((x - Vector{{1, 1, 0.5, 1, 1}}).norm(), 1e-15) << "the refused changes left no trace";
}

/// The mesh without the `gone` elements (its nodes all kept).
mesh::TetMesh cut_mesh(const mesh::TetMesh& mesh, const std::vector<bool>& gone) {
  mesh::TetMesh cut = mesh;
  cut.tets.clear();
  for (std::size_t e = 0; e < mesh.tets.size(); ++e)
    if (!gone[e]) cut.tets.push_back(mesh.tets[e]);
  cut.sets.clear();  // their element lists are the uncut mesh's
  return cut;
}

/// diag(values) as a sparse matrix.
SparseMatrix diagonal(const Vector& values) {
  std::vector<Eigen::Triplet<double>> entries;
  for (Index i = 0; i < values.size(); ++i) entries.emplace_back(i, i, values[i]);
  SparseMatrix D(values.size(), values.size());
  D.setFromTriplets(entries.begin(), entries.end());
  return D;
}

TEST(ElementRemoval, TheUpdatedEffectiveStiffnessIsTheOneRebuiltFromTheCutMesh) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(0.05, 0.03, 0.02, 0.006);
  fem::Constraints constraints(mesh.num_nodes());
  constraints.fix_set(mesh, "x0");
  const fem::DofMap dofs(constraints);
  const fem::MaterialMap materials(fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8));
  const double dt = 1e-3, c = 4 / (dt * dt) + 2 * 0.8 / dt;  // the trapezoid's K + c M with C = alpha M
  const Index n = dofs.num_free();
  const SparseMatrix K = fem::StiffnessAssembler(mesh, dofs).stiffness(materials);
  const Vector M = fem::lumped_mass(mesh, dofs, materials);
  const double total_mass = fem::lumped_node_mass(mesh, materials).sum();
  Cholesky A;
  A.compute(K + diagonal(c * M));
  // Z by CHOLMOD's multi-column solve here (the dense test above: one solve per column).
  LowRankUpdate update([&](const Vector& b, Vector& x) { A.solve(b, x); }, n,
                       [&](const DenseMatrix& B) { return A.solve_matrix(B); });

  // The cuts: one element; ten more; then every element left around the corner farthest from the
  // held face, which leaves that node with none.
  Index corner = 0;
  for (Index v = 0; v < mesh.num_nodes(); ++v)
    if (mesh.node(static_cast<int>(v)).sum() > mesh.node(static_cast<int>(corner)).sum()) corner = v;
  std::vector<bool> gone(mesh.tets.size(), false);
  std::vector<std::vector<Index>> cuts = {{17}, {}, {}};
  for (Index e = 40; e < 50; ++e) cuts[1].push_back(e);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e)
    for (const int v : mesh.tets[e])
      if (v == corner && e != 17 && (e < 40 || e >= 50)) cuts[2].push_back(static_cast<Index>(e));
  ASSERT_FALSE(cuts[2].empty());
  Vector pins = Vector::Zero(n), mass_change = Vector::Zero(n);
  double removed_mass = 0;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> draw(-1, 1);
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    std::vector<bool> still_there(gone.size());
    for (std::size_t e = 0; e < gone.size(); ++e) still_there[e] = !gone[e];
    const fem::ElementRemoval removal = fem::element_removal(mesh, dofs, materials, cuts[k], c, still_there);
    update.add(removal.dofs, removal.change);
    const Vector mass_before = M + mass_change;  // an orphan's pin: c times its mass before this cut
    for (std::size_t a = 0; a < removal.dofs.size(); ++a)
      mass_change[removal.dofs[a]] += removal.mass_change[static_cast<Index>(a)];
    for (const Index e : cuts[k]) {
      gone[static_cast<std::size_t>(e)] = true;
      removed_mass += 1000 * std::abs(mesh::signed_volume(mesh, e));
    }
    for (const int v : removal.orphan_nodes)
      for (int i = 0; i < 3; ++i)
        if (const int d = dofs.free_dof(v, i); d >= 0) pins[d] = c * mass_before[d];
    if (k == 2) {
      EXPECT_TRUE(std::binary_search(removal.orphan_nodes.begin(), removal.orphan_nodes.end(), static_cast<int>(corner)));
    }

    // From scratch: K and the lumped M of the cut mesh, the same pins.
    const mesh::TetMesh cut = cut_mesh(mesh, gone);
    const Vector rebuilt_mass = fem::lumped_mass(cut, dofs, materials.of(0).rho);
    Cholesky rebuilt;
    rebuilt.compute(fem::StiffnessAssembler(cut, dofs).stiffness(fem::MaterialMap(materials.of(0))) +
                    diagonal(c * rebuilt_mass + pins));
    double worst = 0;
    for (int trial = 0; trial < 3; ++trial) {
      Vector b(n), x(n), expected(n);
      for (Index i = 0; i < n; ++i) b[i] = draw(rng);
      update.solve(b, x);
      rebuilt.solve(b, expected);
      worst = std::max(worst, (x - expected).norm() / expected.norm());
    }
    std::printf("cut %zu: %zu elements, rank %lld: |x - x_rebuilt| / |x_rebuilt| = %.1e\n", k, cuts[k].size(),
                static_cast<long long>(update.rank()), worst);
    EXPECT_LT(worst, 1e-10) << "cut " << k;
    // The lumped mass: the cut mesh's, and in all the uncut mesh's less the removed elements' rho V.
    EXPECT_LT((M + mass_change - rebuilt_mass).lpNorm<Eigen::Infinity>(), 1e-14 * M.lpNorm<Eigen::Infinity>());
    EXPECT_NEAR(fem::lumped_node_mass(cut, materials.of(0).rho).sum(), total_mass - removed_mass, 1e-14 * total_mass);
  }
}

TEST(ElementRemoval, AnElementRemovedTwiceIsNamed) {
  const mesh::TetMesh mesh = mesh::unstructured_box_mesh(0.05, 0.03, 0.02, 0.01);
  fem::Constraints constraints(mesh.num_nodes());
  const fem::DofMap dofs(constraints);
  const fem::MaterialMap materials(fem::Material::from_young_poisson(3000, 0.45, 1000, 0));
  try {
    fem::element_removal(mesh, dofs, materials, {3, 3}, 1.0);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedron 3 is removed twice"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace roifem::solvers
