// Cost per time step of every fixed-step integrator on the paper's models (full brain, setup 1,
// setup 2), measured side by side in one run; setup (factorization) is outside the timed loop.
//   compile with: cmake --build --preset release --target roifem_integrator_benchmark
//   sample run:   build/release/benchmarks/roifem_integrator_benchmark --benchmark_repetitions=5
//                   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "integrators/factory.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::bench {
namespace {

const simulation::ScenarioModel& paper_model(const std::string& which) {
  static std::map<std::string, std::unique_ptr<simulation::ScenarioModel>> cache;
  auto& slot = cache[which];
  if (!slot) slot = simulation::build_scenario_model(scenario::read_scenario(std::string(ROIFEM_SCENARIO_DIR) + "/paper-" + which + ".toml"));
  return *slot;
}

void step(benchmark::State& st, const std::string& model_name, const std::string& method) {
  const auto& sys = paper_model(model_name).system();
  const double dt = 0.05;
  auto integrator = integrators::make_integrator(method, dt);
  model::State state{0, Vector::Zero(sys.size()), Vector::Zero(sys.size())};
  integrator->reset(sys, state);
  long k = 0;
  for (auto _ : st) {
    integrator->advance_to(static_cast<double>(++k) * dt, state);
    benchmark::DoNotOptimize(state.u.data());
  }
  st.counters["dofs"] = static_cast<double>(sys.size());
}

}  // namespace
}  // namespace roifem::bench

int main(int argc, char** argv) {
  using namespace roifem::bench;
  for (const char* model : {"full", "setup1", "setup2"})
    for (const char* method : {"trapezoid", "arkode-trapezoid", "arkode-trapezoid-schur", "arkode-sdirk2",
                               "arkode-sdirk2-schur", "arkode-sdirk2-mass", "arkode-sdirk2-mass-schur", "arkode-ark3-schur",
                               "arkode-esdirk4-schur"}) {
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
