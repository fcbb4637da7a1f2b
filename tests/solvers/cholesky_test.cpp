// SPDX-License-Identifier: GPL-3.0-or-later
// Cholesky with a constrained ordering: a condensed K_eff's dense interface block ordered last
// (one trailing dense supernode) gives the same solve as CHOLMOD's own ordering.
#include "solvers/cholesky.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"

#include <algorithm>

#include "condensation/reduced_model.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/fem_model.hpp"

namespace roifem::solvers {
namespace {

TEST(Cholesky, OrdersTheDenseBlockLastAndSolvesAsTheUnconstrainedFactorDoes) {
  // The paper's setup 1 (shipped brain, 306 ROI nodes): K_eff = K~ + 4/dt^2 M at dt = 0.05 s.
  const mesh::TetMesh mesh = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  const model::FemModel full = model::build_fem_model(mesh, fem::material_preset("paper"), {"base"}, {});
  const roi::RoiSpec spec{.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0, 0, 0.04), .count = 306, .set = {}};
  const auto partition = roi::partition_dofs(full.system.K, *full.dofs, roi::select_roi_nodes(mesh, *full.dofs, spec));
  const condensation::ReducedModel condensed(full.system, partition, *full.dofs);
  const auto& sys = condensed.system();
  const SparseMatrix K_eff = sys.K + 1600.0 * sys.M;
  const std::vector<Index> dense = sys.dense_block_dofs();
  ASSERT_EQ(dense.size(), partition.interface.size());

  Cholesky constrained, free;
  constrained.compute(K_eff, dense);
  free.compute(K_eff);
  // The last |I| columns of the factor are exactly the interface's.
  std::vector<Index> order = constrained.ordering();
  ASSERT_EQ(static_cast<Index>(order.size()), sys.size());
  std::vector<Index> tail(order.end() - static_cast<std::ptrdiff_t>(dense.size()), order.end());
  std::sort(tail.begin(), tail.end());
  EXPECT_EQ(tail, dense);
  std::sort(order.begin(), order.end());
  for (Index k = 0; k < sys.size(); ++k) ASSERT_EQ(order[static_cast<std::size_t>(k)], k);  // a permutation

  const Vector b = Vector::LinSpaced(sys.size(), -1.0, 2.0);
  const Vector x = constrained.solve(b), y = free.solve(b);
  const double residual = (K_eff * x - b).norm() / b.norm(), difference = (x - y).norm() / y.norm();
  std::printf("setup 1 K_eff: factor entries %.0f (interface last) vs %.0f; |K x - b| / |b| %.1e, |x - x_free| / |x| %.1e\n",
              constrained.factor_nonzeros(), free.factor_nonzeros(), residual, difference);
  EXPECT_LT(residual, 1e-12);
  EXPECT_LT(difference, 1e-12);
  EXPECT_THROW(Cholesky().compute(K_eff, {sys.size()}), Error);
}

TEST(Cholesky, AnIndefiniteMatrixIsRefusedNamingItsColumnWhicheverFactorCholmodChooses) {
  // A five-point Laplacian plus the identity on an 8 x 8 grid, its diagonal at node 9 made -5. A
  // simplicial LDL^T factorization runs through a negative pivot without complaint (CHOLMOD stops
  // only at a zero one); a supernodal LL^T stops there. Both are refused, naming column 9.
  const Index m = 8, n = m * m;
  std::vector<Eigen::Triplet<double>> entries;
  for (Index i = 0; i < m; ++i)
    for (Index j = 0; j < m; ++j) {
      const Index k = i * m + j;
      entries.emplace_back(k, k, k == 9 ? -5.0 : 5.0);
      if (i > 0) entries.emplace_back(k, k - m, -1.0);
      if (i + 1 < m) entries.emplace_back(k, k + m, -1.0);
      if (j > 0) entries.emplace_back(k, k - 1, -1.0);
      if (j + 1 < m) entries.emplace_back(k, k + 1, -1.0);
    }
  SparseMatrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  for (const auto kind : {Cholesky::Kind::simplicial, Cholesky::Kind::supernodal, Cholesky::Kind::automatic}) {
    Cholesky factor(kind);
    try {
      factor.compute(A);
      ADD_FAILURE() << "an indefinite matrix factored (kind " << static_cast<int>(kind) << ")";
    } catch (const NotPositiveDefinite& e) {
      EXPECT_EQ(e.column, 9) << e.what();
    }
  }
}

}  // namespace
}  // namespace roifem::solvers
