// SPDX-License-Identifier: GPL-3.0-or-later
#include "distributed/distributed_run.hpp"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ostream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/interrupt.hpp"
#include "common/timer.hpp"
#include "distributed/distributed_trapezoid.hpp"
#include "distributed/root_work.hpp"
#include "fem/element.hpp"
#include "io/hdf5_file.hpp"
#include "io/xdmf.hpp"
#include "simulation/progress.hpp"
#include "simulation/results_recorder.hpp"

namespace roifem::distributed {

ResidentMemory peak_resident_megabytes(MPI_Comm comm) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  double mine = static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss: kB
  ResidentMemory m;
  MPI_Allreduce(&mine, &m.largest, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(&mine, &m.total, 1, MPI_DOUBLE, MPI_SUM, comm);
  malloc_trim(0);                // hand freed heap back to the system first, so that "now" counts what is live
  long pages = 0, resident = 0;  // /proc/self/statm: total and resident pages
  if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(statm);
  }
  double now = static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
  MPI_Allreduce(&now, &m.largest_now, 1, MPI_DOUBLE, MPI_MAX, comm);
  return m;
}

namespace {

/// The energy balance of the run, an observer of its states (model/energy.hpp's, for C = alpha M):
///   kinetic v^T M v / 2 and strain u^T K u / 2; dissipated D += dt v_mid^T C v_mid with
///   v_mid = (v_k + v_k+1) / 2; the loads' work W += (u_k+1 - u_k)^T (f_k + f_k+1) / 2,
/// so that kinetic + strain + D = W exactly for the trapezoidal rule from rest.
class DistributedEnergyLedger {
 public:
  DistributedEnergyLedger(const DistributedModel& model, const DistributedTrapezoid& trapezoid)
      : model_(model),
        trapezoid_(trapezoid),
        u_(model.new_vector()),
        v_(model.new_vector()),
        f_(model.new_vector()),
        f_next_(model.new_vector()),
        work_(model.new_vector()) {
    check(VecCopy(trapezoid.u(), u_.get()), "VecCopy");
    check(VecCopy(trapezoid.v(), v_.get()), "VecCopy");
    model.load_at(trapezoid.t(), f_.get());
    update_state_energies();
  }
  /// After each step.
  void record(double dt) {
    model_.load_at(trapezoid_.t(), f_next_.get());
    PetscScalar w = 0, d = 0;
    check(VecAXPY(f_.get(), 1.0, f_next_.get()), "VecAXPY");                   // f_k + f_k+1
    check(VecWAXPY(work_.get(), -1.0, u_.get(), trapezoid_.u()), "VecWAXPY");  // u_k+1 - u_k
    check(VecDot(work_.get(), f_.get(), &w), "VecDot");
    check(VecAXPBYPCZ(work_.get(), 0.5, 0.5, 0.0, v_.get(), trapezoid_.v()), "VecAXPBYPCZ");  // v_mid
    check(VecPointwiseMult(v_.get(), model_.mass.get(), work_.get()), "VecPointwiseMult");    // M v_mid
    check(VecDot(v_.get(), work_.get(), &d), "VecDot");
    external_work_ += 0.5 * w;
    dissipated_ += dt * model_.alpha * d;
    std::swap(f_, f_next_);
    check(VecCopy(trapezoid_.u(), u_.get()), "VecCopy");
    check(VecCopy(trapezoid_.v(), v_.get()), "VecCopy");
    update_state_energies();
  }
  double kinetic() const { return kinetic_; }
  double strain() const { return strain_; }
  double dissipated() const { return dissipated_; }
  double external_work() const { return external_work_; }

 private:
  void update_state_energies() {
    kinetic_ = trapezoid_.kinetic_energy();
    strain_ = trapezoid_.strain_energy();
  }
  const DistributedModel& model_;
  const DistributedTrapezoid& trapezoid_;
  OwnedVec u_, v_, f_, f_next_, work_;
  double kinetic_ = 0, strain_ = 0, dissipated_ = 0, external_work_ = 0;
};

/// Rank 0's results file: the series appended step by step, the fields every field_every steps.
class RootRecorder {
 public:
  RootRecorder(const scenario::Scenario& sc, const model::FemModel& frame, const std::filesystem::path& out,
               const std::string& integrator)
      : sc_(sc),
        frame_(frame),
        out_(out),
        file_(out / "results.h5"),
        h5_(file_.temporary_path()),
        time_s_(header().appendable("time_s", {})),
        wall_s_(h5_.appendable("step_wall_time_s", {})),
        kinetic_(h5_.appendable("energy/kinetic_J", {})),
        strain_(h5_.appendable("energy/strain_J", {})),
        dissipated_(h5_.appendable("energy/dissipated_J", {})),
        work_(h5_.appendable("energy/external_work_J", {})),
        iterations_(h5_.appendable("ksp_iterations", {})),
        xdmf_{.h5_name = "results.h5",
              .nodes = frame.mesh->num_nodes(),
              .tets = frame.mesh->num_tets(),
              .nodes_per_tet = frame.mesh->is_quadratic() ? 10 : 4} {
    h5_.attribute("integrator", integrator);
  }
  void record(long k, double t, double wall_s, const DistributedEnergyLedger& energy, double iterations, const Vector* u_free) {
    for (auto [series, value] : {std::pair{&time_s_, t},
                                 {&wall_s_, wall_s},
                                 {&kinetic_, energy.kinetic()},
                                 {&strain_, energy.strain()},
                                 {&dissipated_, energy.dissipated()},
                                 {&work_, energy.external_work()},
                                 {&iterations_, iterations}})
      series->append(&value);
    if (u_free) {
      const std::string name = format("fields/displacement_mm_%06ld", k);
      const Vector field_mm = frame_.displacement(*u_free, t) / mm;
      h5_.write(name, std::vector<double>(field_mm.data(), field_mm.data() + field_mm.size()),
                {static_cast<hsize_t>(frame_.mesh->num_nodes()), 3});
      xdmf_.times.push_back(t);
      xdmf_.fields.push_back("/" + name);
    }
    if (k % 50 == 0) h5_.flush();
  }
  void finish(std::ostream& log) {
    h5_.attribute("status", "complete");
    h5_.close();
    file_.commit();
    if (!xdmf_.times.empty()) io::write_xdmf(out_ / "results.xdmf", xdmf_);
    for (const auto& stale : simulation::remove_stale_incomplete(out_))
      log << "removed " << stale.string() << ", an earlier run's that was stopped\n";
  }
  void abandon(const std::string& why) {
    h5_.attribute("status", "incomplete: " + why);
    h5_.close();
    file_.commit_as(out_ / "results.incomplete.h5");
  }

 private:
  io::Hdf5Writer& header() {
    io::write_mesh(h5_, *frame_.mesh);
    h5_.text("scenario", sc_.resolved_toml());
    return h5_;
  }
  const scenario::Scenario& sc_;
  const model::FemModel& frame_;
  std::filesystem::path out_;
  AtomicFile file_;
  io::Hdf5Writer h5_;
  io::AppendableDataset time_s_, wall_s_, kinetic_, strain_, dissipated_, work_, iterations_;
  io::XdmfSeries xdmf_;
};

}  // namespace

DistributedRunSummary run_distributed(const scenario::Scenario& sc, const std::filesystem::path& out, std::ostream& log,
                                      MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  DistributedRunSummary summary;
  MPI_Comm_size(comm, &summary.ranks);
  check_distributable(sc);
  if (sc.rtol)
    throw InputError("roifem-mpi: scenario " + sc.file.string() + " sets rtol; the distributed model steps at a fixed dt");
  on_root(comm, [&] { check_output_directory(out); });  // before any work
  const Stopwatch setup;
  const std::unique_ptr<ScenarioFrame> built = scenario_frame(sc);
  const mesh::TetMesh& mesh = built->mesh;
  const model::FemModel& frame = built->model;
  const DistributedModel model = distribute_model(frame, comm);
  DistributedTrapezoid trapezoid(model, sc.dt);
  check_options_used("once K_eff's solver was set up");
  summary.dofs = model.dofs();
  summary.solver = trapezoid.solver();
  summary.setup_s = setup.seconds();
  const std::string integrator = format("trapezoid (PETSc, %s, %d ranks)", summary.solver.c_str(), summary.ranks);
  if (rank == 0) {
    log << format("%s: full model, %ld dofs on %d ranks (%ld nodes, %ld elements, %s), %s\n", sc.file.string().c_str(),
                  summary.dofs, summary.ranks, static_cast<long>(mesh.num_nodes()), static_cast<long>(mesh.num_tets()),
                  std::string(fem::element_name(sc.element)).c_str(), integrator.c_str());
    if (sc.roi) log << "  (the scenario's [roi] is for roifem run: here every free node is dynamic)\n";
    for (const auto& w : frame.warnings) log << "warning: " << w << '\n';
    log << format("setup %.2f s (read, partition, assemble, set up K_eff's solver)\n", summary.setup_s);
  }
  std::unique_ptr<RootRecorder> recorder;
  on_root(comm, [&] { recorder = std::make_unique<RootRecorder>(sc, frame, out, integrator); });
  DistributedEnergyLedger energy(model, trapezoid);
  auto record = [&](long k, double wall_s) {
    if (k > 0) energy.record(sc.dt);
    const bool field = sc.field_every > 0 && k % sc.field_every == 0;
    const Vector u = field ? model.gather(trapezoid.u(), false) : Vector();
    on_root(comm, [&] {
      recorder->record(k, trapezoid.t(), wall_s, energy, k > 0 ? trapezoid.last_iterations() : 0, field ? &u : nullptr);
    });
  };
  std::vector<double> step_s;
  const InterruptGuard interrupts;
  try {
    record(0, 0.0);
    simulation::ProgressReporter progress(rank == 0 ? "roifem-mpi" : "", rank == 0 ? sc.steps : 0);
    for (long k = 1; k <= sc.steps; ++k) {
      const Stopwatch clock;
      trapezoid.step();
      step_s.push_back(clock.seconds());
      record(k, step_s.back());
      if (rank == 0) progress.update(k, format("%d KSP iterations", static_cast<int>(trapezoid.last_iterations())));
      // A signal reaches the ranks at different steps (mpirun forwards it, a batch system sends it
      // to each): they agree after every step, so that all stop after the same one.
      if (const int signal_number = agreed_signal(comm, InterruptGuard::signal_received()))
        throw Agreed<Interrupted>(signal_number, format("interrupted by signal %d after step %ld of %ld (t = %g s)",
                                                        signal_number, k, sc.steps, trapezoid.t()));
    }
  } catch (const Error& e) {
    if (recorder) {
      recorder->abandon(e.what());
      if (dynamic_cast<const Interrupted*>(&e) != nullptr)
        log << "\nstopped: " << e.what() << "\nkept every completed step in " << (out / "results.incomplete.h5").string()
            << " (status: incomplete)\n";
    }
    throw;
  }
  on_root(comm, [&] { recorder->finish(log); });
  std::nth_element(step_s.begin(), step_s.begin() + static_cast<long>(step_s.size() / 2), step_s.end());
  summary.steps = sc.steps;
  summary.step_s_median = step_s.empty() ? 0 : step_s[step_s.size() / 2];
  summary.iterations_per_step =
      sc.steps > 0 ? static_cast<double>(trapezoid.total_iterations()) / static_cast<double>(sc.steps) : 0;
  summary.final_kinetic_J = energy.kinetic();
  summary.final_strain_J = energy.strain();
  summary.final_dissipated_J = energy.dissipated();
  summary.final_work_J = energy.external_work();
  const ResidentMemory memory = peak_resident_megabytes(comm);
  summary.peak_rss_mb = memory.largest;
  summary.total_rss_mb = memory.total;
  summary.now_rss_mb = memory.largest_now;
  if (rank == 0)
    log << format(
        "done: %ld steps, median %.4f s per step, %.1f KSP iterations per step; final kinetic %.3e J, strain %.3e J, "
        "work %.3e J, dissipated %.3e J; "
        "peak memory %.0f MB on one rank, %.0f MB on all (%.0f MB on one rank at the end)\nresults: %s (ParaView: "
        "results.xdmf)\n",
        summary.steps, summary.step_s_median, summary.iterations_per_step, summary.final_kinetic_J, summary.final_strain_J,
        summary.final_work_J, summary.final_dissipated_J, summary.peak_rss_mb, summary.total_rss_mb, summary.now_rss_mb,
        (out / "results.h5").string().c_str());
  return summary;
}

}  // namespace roifem::distributed
