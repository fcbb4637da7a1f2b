// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/blas_threads.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include "mesh/gmsh_reader.hpp"
#include "model/fem_model.hpp"
#include "solvers/cholesky.hpp"
#include "solvers/serial_openmp.hpp"

namespace roifem::solvers {
namespace {

TEST(BlasThreadsScope, SetsTheCountForItsScopeAndRestoresTheOneItFound) {
  if (!BlasThreadsScope::controllable()) GTEST_SKIP() << "the BLAS is not OpenBLAS: nothing to set";
  const int before = BlasThreadsScope::current();
  {
    const BlasThreadsScope two(2);
    EXPECT_EQ(BlasThreadsScope::current(), 2);
    {
      const BlasThreadsScope one(1);
      EXPECT_EQ(BlasThreadsScope::current(), 1);
      const BlasThreadsScope same(BlasThreadsScope::unchanged);
      EXPECT_EQ(BlasThreadsScope::current(), 1);
    }
    EXPECT_EQ(BlasThreadsScope::current(), 2);
  }
  EXPECT_EQ(BlasThreadsScope::current(), before);
}

TEST(BlasThreadsScope, ASmallSupernodalSolveLeavesTheCountAsItFoundIt) {
  if (!BlasThreadsScope::controllable()) GTEST_SKIP() << "the BLAS is not OpenBLAS: nothing to set";
  const mesh::TetMesh mesh = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  const SparseMatrix K = model::build_fem_model(mesh, fem::material_preset("paper"), {"base"}, {}).system.K;
  Cholesky supernodal(Cholesky::Kind::supernodal), simplicial(Cholesky::Kind::simplicial);
  supernodal.compute(K);
  simplicial.compute(K);
  const Vector b = Vector::LinSpaced(K.rows(), -1.0, 2.0);
  const BlasThreadsScope two(2);
  const Vector x = supernodal.solve(b);
  EXPECT_EQ(BlasThreadsScope::current(), 2);
  // The one-thread solve is the same solve: it matches the simplicial factor's (no BLAS) answer.
  EXPECT_LT((x - simplicial.solve(b)).norm(), 1e-10 * x.norm());
  EXPECT_LT((K * x - b).norm(), 1e-10 * b.norm());
}

// CHOLMOD's fixed 4-thread regions run on one thread inside the scope, and the levels come back.
TEST(SerialOpenMpScope, RegionsRunOnOneThreadInsideAndAsBeforeAfter) {
  const int levels = omp_get_max_active_levels();
  auto threads_in_a_region_of_four = [] {
    int seen = 0;
#pragma omp parallel num_threads(4)
    {
#pragma omp single
      seen = omp_get_num_threads();
    }
    return seen;
  };
  {
    const SerialOpenMpScope serial(true);
    EXPECT_EQ(threads_in_a_region_of_four(), 1);
  }
  EXPECT_EQ(omp_get_max_active_levels(), levels);
  {
    const SerialOpenMpScope unchanged(false);
    EXPECT_EQ(omp_get_max_active_levels(), levels);
  }
  if (levels > 0) {
    EXPECT_EQ(threads_in_a_region_of_four(), 4);
  }
}

}  // namespace
}  // namespace roifem::solvers
