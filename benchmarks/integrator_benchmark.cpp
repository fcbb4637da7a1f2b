// SPDX-License-Identifier: GPL-3.0-or-later
// Cost per time step of every fixed-step integrator on the paper's models (full brain, setup 1,
// setup 2), measured side by side in one run; setup (factorization) is outside the timed loop.
//   compile with: cmake --build --preset release --target roifem_integrator_benchmark
//   sample run:   build/release/benchmarks/roifem_integrator_benchmark --benchmark_repetitions=5
//                   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "integrators/arkode.hpp"
#include "integrators/factory.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_model.hpp"
#include "solvers/cholesky.hpp"

namespace roifem::bench {
namespace {

const simulation::ScenarioModel& paper_model(const std::string& which) {
  static std::map<std::string, std::unique_ptr<simulation::ScenarioModel>> cache;
  auto& slot = cache[which];
  if (!slot)
    slot =
        simulation::build_scenario_model(scenario::read_scenario(std::string(ROIFEM_SCENARIO_DIR) + "/paper-" + which + ".toml"));
  return *slot;
}

void step(benchmark::State& st, const std::string& model_name, const std::string& method) {
  const auto& sys = paper_model(model_name).system();
  const double dt = 0.05;
  auto integrator = integrators::make_integrator(method, dt);
  model::State state = model::State::at_rest(sys.size());
  integrator->reset(sys, state);
  long k = 0;
  for (auto _ : st) {
    integrator->advance_to(static_cast<double>(++k) * dt, state);
    benchmark::DoNotOptimize(state.u.data());
  }
  st.counters["dofs"] = static_cast<double>(sys.size());
}

// The two kernels a step is made of: a product with the condensed K (sparse part plus dense
// interface block) and one solve with the factor of K + 2/dt C + 4/dt^2 M.
void stiffness_product(benchmark::State& st, const std::string& model_name) {
  const auto& sys = paper_model(model_name).system();
  const Vector x = Vector::Ones(sys.size());
  Vector y(sys.size());
  for (auto _ : st) {
    sys.apply_stiffness(x, y);
    benchmark::DoNotOptimize(y.data());
  }
}

void factor_solve(benchmark::State& st, const std::string& model_name) {
  const auto& sys = paper_model(model_name).system();
  const double dt = 0.05;
  solvers::Cholesky factor;
  factor.compute(SparseMatrix(sys.K + (2.0 / dt) * sys.C + (4.0 / (dt * dt)) * sys.M));
  const Vector b = Vector::Ones(sys.size());
  Vector x(sys.size());
  for (auto _ : st) {
    factor.solve(b, x);
    benchmark::DoNotOptimize(x.data());
  }
}

// Setup of an integrator: reset (patterns, analysis, factorization) and its first step, where
// SUNDIALS does its first linear-solver setup. factor_ms: the seconds inside factorizations
// (KLU: analysis and first factorization; CHOLMOD for trapezoid and -schur).
void setup(benchmark::State& st, const std::string& model_name, const std::string& method,
           integrators::sundials::KluOrdering ordering) {
  const auto& sys = paper_model(model_name).system();
  const double dt = 0.05;
  double factor_s = 0;
  for (auto _ : st) {
    std::unique_ptr<integrators::Integrator> integrator;
    if (ordering == integrators::sundials::KluOrdering::amd) {
      integrator = integrators::make_integrator(method, dt);
    } else {
      auto description = integrators::arkode_method(method);
      description.klu_ordering = ordering;
      integrator = std::make_unique<integrators::Arkode>(description, integrators::StepControl{.dt = dt});
    }
    model::State state = model::State::at_rest(sys.size());
    integrator->reset(sys, state);
    integrator->advance_to(dt, state);
    factor_s = integrator->stats().factorization_s;
  }
  st.counters["factor_ms"] = factor_s * 1e3;
}

}  // namespace
}  // namespace roifem::bench

int main(int argc, char** argv) {
  using namespace roifem::bench;
  for (const char* model : {"full", "setup1", "setup2"}) {
    benchmark::RegisterBenchmark((std::string("kernel/") + model + "/K_product").c_str(), stiffness_product, model)
        ->Unit(benchmark::kMicrosecond)
        ->MinTime(0.2);
    benchmark::RegisterBenchmark((std::string("kernel/") + model + "/factor_solve").c_str(), factor_solve, model)
        ->Unit(benchmark::kMicrosecond)
        ->MinTime(0.2);
  }
  using roifem::integrators::sundials::KluOrdering;
  for (const char* model : {"full", "setup1", "setup2"}) {
    for (const char* method : {"trapezoid", "arkode-sdirk2-schur"})
      benchmark::RegisterBenchmark((std::string("setup/") + model + "/" + method).c_str(), setup, model, method, KluOrdering::amd)
          ->Unit(benchmark::kMillisecond);
    for (auto [ordering, label] : {std::pair{KluOrdering::amd, "amd"}, std::pair{KluOrdering::colamd, "colamd"}})
      benchmark::RegisterBenchmark((std::string("setup/") + model + "/arkode-sdirk2/klu-" + label).c_str(), setup, model,
                                   "arkode-sdirk2", ordering)
          ->Unit(benchmark::kMillisecond);
  }
  for (const char* model : {"full", "setup1", "setup2"})
    for (const char* method : {"trapezoid", "arkode-trapezoid", "arkode-trapezoid-schur", "arkode-sdirk2", "arkode-sdirk2-schur",
                               "arkode-sdirk2-mass", "arkode-sdirk2-mass-schur", "arkode-ark3-schur", "arkode-esdirk4-schur"}) {
      // GSL's implicit rk4imp does not converge its stage iteration at dt = 0.05 s on these models
      // (w_max dt ~ 100); GSL is compared adaptively in `roifem compare` instead.
      benchmark::RegisterBenchmark((std::string("step/") + model + "/" + method).c_str(), step, model, method)
          ->Unit(benchmark::kMicrosecond)
          ->MinTime(0.2);
    }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
