// SPDX-License-Identifier: GPL-3.0-or-later
// Foundation benchmarks: mesh read, stiffness assembly (pattern + values; the 10-node tetrahedron's
// values too, up to 20k nodes), Cholesky factorization
// of K (base fixed), and the condensation of K onto an ROI two ways, side by side: one partial
// factorization with the interface ordered last (what roifem does), and the straightforward
// factor of K_ss followed by one solve per interface column (X = K_ss^-1 K_sI, S = K_Is X).
//   compile with: cmake --build --preset release --target roifem_fem_benchmark
//   sample run:   ROIFEM_BENCH_SIZES=800,20000,100000 build/release/benchmarks/roifem_fem_benchmark
//                   --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>

#include "brain_meshes.hpp"
#include "fem/assembly.hpp"
#include "fem/hyperelastic_assembly.hpp"
#include "fem/static_solve.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/quadratic_mesh.hpp"
#include "roi/roi.hpp"
#include "solvers/partial_cholesky.hpp"

namespace roifem::bench {
namespace {

struct Model {
  mesh::TetMesh mesh;
  std::unique_ptr<fem::DofMap> dofs;
  /// The brain at `nodes` nodes; `quadratic`: with the edges' midpoints, for the 10-node tetrahedron.
  explicit Model(long nodes, bool quadratic = false)
      : mesh(quadratic ? mesh::with_midside_nodes(mesh::read_mesh(brain_mesh_file(nodes)))
                       : mesh::read_mesh(brain_mesh_file(nodes))) {
    fem::Constraints constraints(mesh.num_nodes());
    constraints.fix_set(mesh, "base");
    dofs = std::make_unique<fem::DofMap>(constraints);
  }
};

const fem::Material material = fem::material_preset("paper");

void read_mesh(benchmark::State& state, long nodes) {
  const auto file = brain_mesh_file(nodes);
  for (auto _ : state) benchmark::DoNotOptimize(mesh::read_mesh(file));
}

void assemble_pattern(benchmark::State& state, long nodes) {
  const Model model(nodes);
  for (auto _ : state) benchmark::DoNotOptimize(fem::StiffnessAssembler(model.mesh, *model.dofs));
}

void assemble_values(benchmark::State& state, long nodes) {
  const Model model(nodes);
  const fem::StiffnessAssembler assembler(model.mesh, *model.dofs);
  for (auto _ : state) benchmark::DoNotOptimize(assembler.stiffness(material));
  state.counters["nnz"] = static_cast<double>(assembler.nonzeros());
}

/// The 10-node tetrahedron's K on the same brain (its vertices; ~7x the dofs).
void assemble_values_tet10(benchmark::State& state, long nodes) {
  const Model model(nodes, true);
  const fem::StiffnessAssembler assembler(model.mesh, *model.dofs);
  for (auto _ : state) benchmark::DoNotOptimize(assembler.stiffness(material));
  state.counters["nnz"] = static_cast<double>(assembler.nonzeros());
  state.counters["dofs"] = static_cast<double>(model.dofs->num_free());
}

void assemble_total(benchmark::State& state, long nodes) {
  const Model model(nodes);
  for (auto _ : state) {
    const fem::StiffnessAssembler assembler(model.mesh, *model.dofs);
    benchmark::DoNotOptimize(assembler.stiffness(material));
  }
}

void factorize(benchmark::State& state, long nodes) {
  const Model model(nodes);
  const SparseMatrix K = fem::StiffnessAssembler(model.mesh, *model.dofs).stiffness(material);
  solvers::Cholesky cholesky;
  for (auto _ : state) {
    cholesky.compute(K);  // analysis (ordering) + numeric factorization
  }
  state.counters["dofs"] = static_cast<double>(K.rows());
  state.counters["nnz_L"] = cholesky.factor_nonzeros();
}

/// K and the static / interface split for an ROI of `roi_nodes` nodes nearest the target (0, 0, 40) mm.
struct Split {
  SparseMatrix K;
  std::vector<Index> s, interface_dofs;
  Split(const Model& model, Index roi_nodes) : K(fem::StiffnessAssembler(model.mesh, *model.dofs).stiffness(material)) {
    const roi::RoiSpec spec{
        .kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0, 0, 40 * mm), .radius = 0, .count = roi_nodes, .set = {}};
    const auto p = roi::partition_dofs(K, *model.dofs, roi::select_roi_nodes(model.mesh, *model.dofs, spec));
    s = p.s;
    for (Index k : p.interface) interface_dofs.push_back(p.d[static_cast<std::size_t>(k)]);
  }
};

void condense_partial_factorization(benchmark::State& state, long nodes, Index roi_nodes) {
  const Model model(nodes);
  const Split split(model, roi_nodes);
  std::vector<Index> both = split.s;
  both.insert(both.end(), split.interface_dofs.begin(), split.interface_dofs.end());
  std::sort(both.begin(), both.end());
  std::vector<Index> trailing;
  for (Index dof : split.interface_dofs) trailing.push_back(std::lower_bound(both.begin(), both.end(), dof) - both.begin());
  const SparseMatrix A = roi::submatrix(split.K, both, both);
  for (auto _ : state) {
    const solvers::PartialCholesky factor(A, trailing);
    benchmark::DoNotOptimize(factor.trailing_schur_complement());
  }
  state.counters["interface_dofs"] = static_cast<double>(trailing.size());
}

void condense_column_solves(benchmark::State& state, long nodes, Index roi_nodes) {
  const Model model(nodes);
  const Split split(model, roi_nodes);
  const SparseMatrix K_ss = roi::submatrix(split.K, split.s, split.s);
  const DenseMatrix K_sI(roi::submatrix(split.K, split.s, split.interface_dofs));
  for (auto _ : state) {
    solvers::Cholesky factor;
    factor.compute(K_ss);
    const DenseMatrix X = factor.solve_matrix(K_sI);
    benchmark::DoNotOptimize(DenseMatrix(K_sI.transpose() * X));
  }
  state.counters["interface_dofs"] = static_cast<double>(split.interface_dofs.size());
}

/// The neo-Hookean law's force over every element at a displacement of about 1% strain
/// (`excess`: what it adds to the linear elements, the haptic tick's inner loop), per element.
void neo_hookean_force(benchmark::State& state, long nodes, bool excess) {
  const Model model(nodes);
  fem::Material tissue = material;
  tissue.model = fem::MaterialModel::neo_hookean;
  const fem::HyperelasticAssembler assembler(model.mesh, *model.dofs, fem::MaterialMap(tissue));
  Vector u(3 * model.mesh.num_nodes());
  for (int n = 0; n < model.mesh.num_nodes(); ++n)
    u.segment<3>(3 * n) = 0.01 * model.mesh.node(n).cwiseProduct(Vec3(1, -0.5, 0.3));
  Vector f(model.dofs->num_free()), u_free(model.dofs->num_free());
  for (Index i = 0; i < u_free.size(); ++i) u_free[i] = u[model.dofs->full_dof(i)];
  for (auto _ : state) {
    if (excess)
      assembler.excess_force_free(u_free, f);
    else
      assembler.force(u, f);
    benchmark::DoNotOptimize(f.data());
  }
  // Seconds per element (printed with its SI prefix: "250n" is 250 ns).
  state.counters["per_element"] = benchmark::Counter(static_cast<double>(model.mesh.num_tets()),
                                                     benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace
}  // namespace roifem::bench

int main(int argc, char** argv) {
  using namespace roifem::bench;
  for (long n : bench_sizes("800,20000,100000")) {
    const std::string suffix = "/nodes:" + std::to_string(n);
    benchmark::RegisterBenchmark(("read_mesh" + suffix).c_str(), read_mesh, n)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("assemble_pattern" + suffix).c_str(), assemble_pattern, n)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("assemble_values" + suffix).c_str(), assemble_values, n)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("assemble_total" + suffix).c_str(), assemble_total, n)->Unit(benchmark::kMillisecond);
    if (n <= 20000)  // 100k vertices: 2.4M dofs, a few GB of K
      benchmark::RegisterBenchmark(("assemble_values_tet10" + suffix).c_str(), assemble_values_tet10, n)
          ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("factorize" + suffix).c_str(), factorize, n)->Unit(benchmark::kMillisecond);
    if (n <= 20000) {
      benchmark::RegisterBenchmark(("neo_hookean_force" + suffix).c_str(), neo_hookean_force, n, false)
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("neo_hookean_excess" + suffix).c_str(), neo_hookean_force, n, true)
          ->Unit(benchmark::kMillisecond);
    }
    for (long roi : {300L, 1000L}) {
      if (roi * 2 > n) continue;
      const std::string which = suffix + "/roi:" + std::to_string(roi);
      benchmark::RegisterBenchmark(("condense/partial_factorization" + which).c_str(), condense_partial_factorization, n, roi)
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("condense/column_solves" + which).c_str(), condense_column_solves, n, roi)
          ->Unit(benchmark::kMillisecond);
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
