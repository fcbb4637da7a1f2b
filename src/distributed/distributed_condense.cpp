// SPDX-License-Identifier: GPL-3.0-or-later
#include "distributed/distributed_condense.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/timer.hpp"
#include "distributed/condensed_roi.hpp"
#include "distributed/distributed_run.hpp"
#include "distributed/mumps_condensation.hpp"
#include "distributed/root_work.hpp"
#include "integrators/trapezoid.hpp"
#include "io/hdf5_file.hpp"
#include "roi/roi.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::distributed {

namespace {

/// The ROI's peak displacement over a serial trapezoid run of `system` (m).
double roi_peak(const model::SecondOrderSystem& system, const scenario::Scenario& sc) {
  integrators::Trapezoid trapezoid(sc.dt);
  auto state = model::State::at_rest(system.size());
  trapezoid.reset(system, state);
  double peak = 0;
  for (long k = 0; k < sc.steps; ++k) {
    trapezoid.step(state);
    for (Index i = 0; i + 2 < state.u.size(); i += 3) peak = std::max(peak, state.u.segment<3>(i).norm());
  }
  return peak;
}

}  // namespace

void condense_distributed(const scenario::Scenario& sc, const std::filesystem::path& out, bool check_serial, std::ostream& log,
                          MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (!sc.roi) throw InputError("roifem-mpi condense: scenario " + sc.file.string() + " has no [roi] to condense onto");
  on_root(comm, [&] { check_output_directory(out); });
  const auto built = scenario_frame(sc);
  const mesh::TetMesh& mesh = built->mesh;
  const model::FemModel& frame = built->model;
  const std::vector<int> roi_nodes = roi::select_roi_nodes(mesh, *frame.dofs, *sc.roi);
  const std::vector<Index> d = roi_free_dofs(*frame.dofs, roi_nodes);
  const Stopwatch clock;
  const DistributedModel model = distribute_model(frame, comm);
  const double assembly_s = clock.seconds();
  const DistributedCondensation condensed = condense_with_mumps(model, d);
  check_options_used("once MUMPS factored K");
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const ResidentMemory memory = peak_resident_megabytes(comm);
  if (rank != 0) return;
  log << format(
      "%s: K~ on %zu ROI dofs (%zu nodes) from %ld dofs on %d ranks: assembly %.2f s, MUMPS analysis + factorization "
      "with the Schur complement %.2f s, %.3g entries in the factors, MUMPS peak %.0f MB on one rank; process peaks %.0f MB on "
      "one "
      "rank, %.0f MB on all\n",
      sc.file.string().c_str(), d.size(), roi_nodes.size(), static_cast<long>(model.dofs()), ranks, assembly_s,
      condensed.factor_s, condensed.factor_entries, condensed.peak_megabytes, memory.largest, memory.total);
  const model::SecondOrderSystem roi = condensed_roi_system(model, condensed, d);
  const double peak = roi_peak(roi, sc);
  log << format("the condensed ROI model, trapezoid at dt = %g s over %ld steps on one rank: peak %.6g mm\n", sc.dt, sc.steps,
                peak / mm);
  {
    AtomicFile file(out / "condensation.h5");
    io::Hdf5Writer h5(file.temporary_path());
    const auto s = static_cast<hsize_t>(d.size());
    h5.write("K_tilde", std::vector<double>(condensed.K_tilde.data(), condensed.K_tilde.data() + condensed.K_tilde.size()),
             {s, s});
    std::vector<double> f;
    for (const Vector& p : condensed.f_tilde) f.insert(f.end(), p.data(), p.data() + p.size());
    h5.write("f_tilde", f, {condensed.f_tilde.size(), s});
    h5.write("roi/nodes", roi_nodes, {roi_nodes.size()});
    std::vector<int> dofs(d.begin(), d.end());
    h5.write("roi/free_dofs", dofs, {dofs.size()});
    h5.text("scenario", sc.resolved_toml());
    h5.close();
    file.commit();
  }
  log << "written: " << (out / "condensation.h5").string() << " (K_tilde, f_tilde per load pattern, the ROI's nodes and dofs)\n";
  if (!check_serial) return;
  if (!sc.reduction.is_static_condensation())
    throw InputError("roifem-mpi condense --check: the scenario's reduction is not static condensation");
  const auto serial = simulation::build_scenario_model(sc);
  const model::SecondOrderSystem& reference = serial->system();
  const DenseMatrix K_ref(reference.K);
  double f_gap = 0, f_scale = 0;
  for (std::size_t k = 0; k < condensed.f_tilde.size(); ++k) {
    f_gap = std::max(f_gap, (condensed.f_tilde[k] - reference.load.terms()[k].pattern).lpNorm<Eigen::Infinity>());
    f_scale = std::max(f_scale, reference.load.terms()[k].pattern.lpNorm<Eigen::Infinity>());
  }
  const double peak_ref = roi_peak(reference, sc);
  log << format(
      "serial condensation (one process, CHOLMOD): max |K~_mumps - K~| / max |K~| = %.2e, max |f~_mumps - f~| / max |f~| = %.2e, "
      "ROI peak %.6g mm (difference %.2e relative)\n",
      (condensed.K_tilde - K_ref).lpNorm<Eigen::Infinity>() / K_ref.lpNorm<Eigen::Infinity>(),
      f_scale > 0 ? f_gap / f_scale : 0.0, peak_ref / mm, std::abs(peak - peak_ref) / peak_ref);
}

}  // namespace roifem::distributed
