// roifem-mpi: the full dynamic model and the ROI's condensation on P ranks (PETSc, MPI, MUMPS).
// CLI only: the work is src/distributed's. Run under MPI:
//   mpirun -n 2 roifem-mpi run scenarios/paper-full.toml --out results/mpi
//   mpirun -n 2 roifem-mpi run scenarios/paper-full.toml --out results/mpi -- -ksp_type cg -pc_type gamg
//   mpirun -n 2 roifem-mpi condense scenarios/paper-setup1.toml --out results/condensed --check
// Everything after -- goes to PETSc's options database.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/timer.hpp"
#include "distributed/condensed_roi.hpp"
#include "distributed/distributed_run.hpp"
#include "distributed/petsc_ts.hpp"
#include "distributed/root_work.hpp"
#include "experiments/compare_experiment.hpp"
#include "fem/element.hpp"
#include "integrators/trapezoid.hpp"
#include "io/csv.hpp"
#include "io/hdf5_file.hpp"
#include "roi/roi.hpp"
#include "simulation/scenario_model.hpp"

namespace {

using roifem::Index;
using roifem::Vector;
namespace distributed = roifem::distributed;

/// The ROI's peak displacement over a serial trapezoid run of `system` (m).
double roi_peak(const roifem::model::SecondOrderSystem& system, const roifem::scenario::Scenario& sc) {
  roifem::integrators::Trapezoid trapezoid(sc.dt);
  auto state = roifem::model::State::at_rest(system.size());
  trapezoid.reset(system, state);
  double peak = 0;
  for (long k = 0; k < sc.steps; ++k) {
    trapezoid.step(state);
    for (Index i = 0; i + 2 < state.u.size(); i += 3) peak = std::max(peak, state.u.segment<3>(i).norm());
  }
  return peak;
}

void condense(const roifem::scenario::Scenario& sc, const std::filesystem::path& out, bool check_serial, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (!sc.roi) throw roifem::InputError("roifem-mpi condense: scenario " + sc.file.string() + " has no [roi] to condense onto");
  distributed::on_root(comm, [&] { roifem::check_output_directory(out); });
  const auto built = distributed::scenario_frame(sc);
  const roifem::mesh::TetMesh& mesh = built->mesh;
  const roifem::model::FemModel& frame = built->model;
  const std::vector<int> roi_nodes = roifem::roi::select_roi_nodes(mesh, *frame.dofs, *sc.roi);
  const std::vector<Index> d = distributed::roi_free_dofs(*frame.dofs, roi_nodes);
  const roifem::Stopwatch clock;
  const distributed::DistributedModel model = distributed::distribute_model(frame, comm);
  const double assembly_s = clock.seconds();
  const distributed::DistributedCondensation condensed = distributed::condense_with_mumps(model, d);
  distributed::check_options_used("once MUMPS factored K");
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const distributed::ResidentMemory memory = distributed::peak_resident_megabytes(comm);
  if (rank != 0) return;
  std::cout << roifem::io::format(
      "%s: K~ on %zu ROI dofs (%zu nodes) from %ld dofs on %d ranks: assembly %.2f s, MUMPS analysis + factorization "
      "with the Schur complement %.2f s, %.3g entries in the factors, MUMPS peak %.0f MB on one rank; process peaks %.0f MB on "
      "one "
      "rank, %.0f MB on all\n",
      sc.file.string().c_str(), d.size(), roi_nodes.size(), static_cast<long>(model.dofs()), ranks, assembly_s,
      condensed.factor_s, condensed.factor_entries, condensed.peak_megabytes, memory.largest, memory.total);
  const roifem::model::SecondOrderSystem roi = distributed::condensed_roi_system(model, condensed, d);
  const double peak = roi_peak(roi, sc);
  std::cout << roifem::io::format("the condensed ROI model, trapezoid at dt = %g s over %ld steps on one rank: peak %.6g mm\n",
                                  sc.dt, sc.steps, peak / roifem::mm);
  {
    roifem::AtomicFile file(out / "condensation.h5");
    roifem::io::Hdf5Writer h5(file.temporary_path());
    const auto s = static_cast<hsize_t>(d.size());
    h5.write("K_tilde", std::vector<double>(condensed.K_tilde.data(), condensed.K_tilde.data() + condensed.K_tilde.size()),
             {s, s});
    std::vector<double> f;
    for (const Vector& p : condensed.f_tilde) f.insert(f.end(), p.data(), p.data() + p.size());
    h5.write("f_tilde", f, {condensed.f_tilde.size(), s});
    h5.write("roi/nodes", roi_nodes, {roi_nodes.size()});
    std::vector<int> dofs(d.begin(), d.end());
    h5.write("roi/free_dofs", dofs, {dofs.size()});
    h5.attribute("scenario", sc.resolved_toml());
    h5.close();
    file.commit();
  }
  std::cout << "written: " << (out / "condensation.h5").string()
            << " (K_tilde, f_tilde per load pattern, the ROI's nodes and dofs)\n";
  if (!check_serial) return;
  if (!sc.reduction.is_static_condensation())
    throw roifem::InputError("roifem-mpi condense --check: the scenario's reduction is not static condensation");
  const auto serial = roifem::simulation::build_scenario_model(sc);
  const roifem::model::SecondOrderSystem& reference = serial->system();
  const roifem::DenseMatrix K_ref(reference.K);
  double f_gap = 0, f_scale = 0;
  for (std::size_t k = 0; k < condensed.f_tilde.size(); ++k) {
    f_gap = std::max(f_gap, (condensed.f_tilde[k] - reference.load.terms()[k].pattern).lpNorm<Eigen::Infinity>());
    f_scale = std::max(f_scale, reference.load.terms()[k].pattern.lpNorm<Eigen::Infinity>());
  }
  const double peak_ref = roi_peak(reference, sc);
  std::cout << roifem::io::format(
      "serial condensation (one process, CHOLMOD): max |K~_mumps - K~| / max |K~| = %.2e, max |f~_mumps - f~| / max |f~| = %.2e, "
      "ROI peak %.6g mm (difference %.2e relative)\n",
      (condensed.K_tilde - K_ref).lpNorm<Eigen::Infinity>() / K_ref.lpNorm<Eigen::Infinity>(),
      f_scale > 0 ? f_gap / f_scale : 0.0, peak_ref / roifem::mm, std::abs(peak - peak_ref) / peak_ref);
}

int run_cli(int argc, char** argv) {
  // roifem-mpi's own arguments before --, PETSc's after it.
  const auto separator = std::find_if(argv, argv + argc, [](const char* a) { return std::strcmp(a, "--") == 0; });
  const int own_argc = static_cast<int>(separator - argv);
  std::vector<char*> petsc_argv{argv[0]};
  if (separator != argv + argc) petsc_argv.insert(petsc_argv.end(), separator + 1, argv + argc);
  petsc_argv.push_back(nullptr);

  CLI::App app{
      "roifem-mpi: the full dynamic model of a scenario and its ROI's static condensation on P ranks (PETSc, MPI, MUMPS).\n"
      "Run under MPI; options after -- go to PETSc, e.g. the solver of K + 2/dt C + 4/dt^2 M:\n"
      "  mpirun -n 2 roifem-mpi run scenarios/paper-full.toml --out results/mpi                  (MUMPS Cholesky)\n"
      "  mpirun -n 2 roifem-mpi run scenarios/paper-full.toml --out results/mpi -- -ksp_type cg -pc_type gamg -ksp_rtol 1e-10\n"
      "  mpirun -n 2 roifem-mpi condense scenarios/paper-setup1.toml --out results/condensed --check\n"
      "  roifem-mpi compare scenarios/paper-setup1.toml --out results/compare-petsc                 (one rank)"};
  app.require_subcommand(1);
  std::filesystem::path scenario_file, out = "results/mpi";
  bool check_serial = false;
  auto* run =
      app.add_subcommand("run", "Integrate the scenario's full model (every free node dynamic) with the trapezoidal rule");
  run->add_option("scenario", scenario_file, "Scenario file (TOML; its mesh, material, supports, loads, dt and steps)")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("--out", out, "Directory for results.h5 and results.xdmf")->capture_default_str();
  roifem::experiments::CompareOptions compare_options;
  auto* compare = app.add_subcommand(
      "compare", "roifem compare with PETSc's integrators added (petsc-alpha2: TSALPHA2, petsc-theta: TSTHETA); one rank");
  compare->add_option("scenario", scenario_file, "Scenario file (.toml); its dt is the output grid")
      ->required()
      ->check(CLI::ExistingFile);
  compare->add_option("--out", compare_options.out, "Output directory")->required();
  compare->add_option("--integrators", compare_options.integrators,
                      "Only these (default: trapezoid, petsc-alpha2, petsc-theta; any of roifem compare's names too)");
  compare->add_option("--t-end", compare_options.t_end, "Simulated time in s (0: the scenario's dt * steps)")
      ->capture_default_str();
  compare->add_option("--fixed-levels", compare_options.fixed_levels, "Fixed steps dt, dt/2, ...")->capture_default_str();
  compare->add_flag("!--no-plots", compare_options.plots, "Skip the PNG plots");
  auto* cond = app.add_subcommand("condense", "Condense the scenario's [roi] from the distributed K by MUMPS's Schur complement");
  cond->add_option("scenario", scenario_file, "Scenario file with an [roi]")->required()->check(CLI::ExistingFile);
  cond->add_option("--out", out, "Directory for condensation.h5")->capture_default_str();
  cond->add_flag("--check", check_serial, "Also condense serially on rank 0 and print the differences");
  try {
    app.parse(own_argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    const distributed::PetscSession session(static_cast<int>(petsc_argv.size()) - 1, petsc_argv.data());
    try {
      // Read and checked alike on every rank: a refusal is printed once, with no MPI_Abort.
      roifem::scenario::Scenario sc;
      distributed::on_every_rank(session.comm(), [&] {
        sc = roifem::scenario::read_scenario(scenario_file);
        if (!compare->parsed()) distributed::check_distributable(sc);
      });
      if (run->parsed()) {
        distributed::run_distributed(sc, out, std::cout, session.comm());
      } else if (compare->parsed()) {
        if (session.size() > 1)
          throw roifem::InputError("roifem-mpi compare runs on one rank (PETSc's integrators on PETSC_COMM_SELF)");
        compare_options.extra_rows = distributed::petsc_ts_rows();
        if (compare_options.integrators.empty()) compare_options.integrators = {"trapezoid", "petsc-alpha2", "petsc-theta"};
        roifem::experiments::run_compare(sc, compare_options, std::cout);
        distributed::check_options_used("by PETSc's integrators over the whole sweep");
      } else {
        condense(sc, out, check_serial, session.comm());
      }
    } catch (const std::exception& e) {
      if (dynamic_cast<const distributed::AgreedByEveryRank*>(&e) != nullptr) {  // every rank is here: say it once
        if (session.rank() == 0)
          std::cerr << "roifem-mpi: " << (dynamic_cast<const roifem::Interrupted*>(&e) ? "" : "error: ") << e.what() << '\n';
        const auto* interrupted = dynamic_cast<const roifem::Interrupted*>(&e);
        return interrupted != nullptr ? 128 + interrupted->signal : 1;
      }
      // One rank's failure must not leave the others waiting in a collective call: stop them all.
      std::cerr << "roifem-mpi: error (rank " << session.rank() << "): " << e.what() << '\n';
      std::cerr.flush();
      std::cout.flush();
      if (session.size() > 1) MPI_Abort(session.comm(), 1);
      return 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "roifem-mpi: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_cli(argc, argv);
  } catch (const std::exception& e) {  // before or after the PETSc session (CLI11's set-up, PetscFinalize)
    std::cerr << "roifem-mpi: error: " << e.what() << '\n';
    return 1;
  }
}
