// Foundation benchmarks: mesh read, stiffness assembly (pattern + values) and Cholesky
// factorization of K (base fixed), on generated brains.
//   compile with: cmake --build --preset release --target roifem_fem_benchmark
//   sample run:   ROIFEM_BENCH_SIZES=800,20000,100000 build/release/benchmarks/roifem_fem_benchmark
//                   --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "brain_meshes.hpp"
#include "fem/assembly.hpp"
#include "fem/static_solve.hpp"
#include "mesh/gmsh_reader.hpp"

namespace roifem::bench {
namespace {

struct Model {
  mesh::TetMesh mesh;
  std::unique_ptr<fem::DofMap> dofs;
  explicit Model(long nodes) : mesh(mesh::read_mesh(brain_mesh_file(nodes))) {
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
    benchmark::RegisterBenchmark(("factorize" + suffix).c_str(), factorize, n)->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
