// SPDX-License-Identifier: GPL-3.0-or-later
#include "distributed/mumps_condensation.hpp"

#include <dmumps_c.h>

#include <string>

#include "common/errors.hpp"
#include "common/timer.hpp"

namespace roifem::distributed {

namespace {

// MUMPS's arrays are 1-based Fortran ones: ICNTL(i) is icntl[i - 1].
constexpr int job_init = -1, job_end = -2, job_solve = 3, job_analyse_factorize = 4;

/// MUMPS's instance for the lifetime of the object (JOB = -1 ... JOB = -2).
class MumpsInstance {
 public:
  explicit MumpsInstance(MPI_Comm comm) {
    id_.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
    id_.par = 1;  // the host works too
    id_.sym = 2;  // symmetric (K is positive definite; 2 keeps MUMPS's pivoting as a guard)
    run(job_init, "initialization");
    icntl(1) = -1;  // no error, diagnostic or global output (failures are reported through INFOG)
    icntl(2) = -1;
    icntl(3) = -1;
    icntl(4) = 0;
  }
  MumpsInstance(const MumpsInstance&) = delete;
  MumpsInstance& operator=(const MumpsInstance&) = delete;
  ~MumpsInstance() {
    id_.job = job_end;
    dmumps_c(&id_);
  }
  MUMPS_INT& icntl(int i) { return id_.icntl[i - 1]; }
  DMUMPS_STRUC_C& id() { return id_; }
  void run(int job, const char* what) {
    id_.job = job;
    dmumps_c(&id_);
    if (id_.infog[0] < 0)
      throw SolverError(std::string("MUMPS: ") + what + " failed: INFOG(1) = " + std::to_string(id_.infog[0]) +
                        ", INFOG(2) = " + std::to_string(id_.infog[1]) +
                        (id_.infog[0] == -10 ? " (the static part is singular: is the brain fixed where the ROI ends?)" : ""));
  }

 private:
  DMUMPS_STRUC_C id_{};
};

}  // namespace

DistributedCondensation condense_with_mumps(const DistributedModel& model, const std::vector<Index>& roi_dofs) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(model.K.get()), &comm), "PetscObjectGetComm");
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (roi_dofs.empty()) throw ModelError("roifem-mpi: the ROI holds no free dof: nothing to condense onto");
  // This rank's rows of K's upper triangle, 1-based.
  std::vector<MUMPS_INT> rows, cols;
  std::vector<double> values;
  PetscInt begin = 0, end = 0;
  check(MatGetOwnershipRange(model.K.get(), &begin, &end), "MatGetOwnershipRange");
  for (PetscInt i = begin; i < end; ++i) {
    PetscInt n = 0;
    const PetscInt* j = nullptr;
    const PetscScalar* a = nullptr;
    check(MatGetRow(model.K.get(), i, &n, &j, &a), "MatGetRow");
    for (PetscInt k = 0; k < n; ++k)
      if (j[k] >= i) {
        rows.push_back(static_cast<MUMPS_INT>(i + 1));
        cols.push_back(static_cast<MUMPS_INT>(j[k] + 1));
        values.push_back(a[k]);
      }
    check(MatRestoreRow(model.K.get(), i, &n, &j, &a), "MatRestoreRow");
  }
  const auto s = static_cast<MUMPS_INT>(roi_dofs.size());
  std::vector<MUMPS_INT> schur_variables;
  schur_variables.reserve(roi_dofs.size());
  for (const Index d : roi_dofs) schur_variables.push_back(static_cast<MUMPS_INT>(model.index_of_free_dof(d) + 1));
  DistributedCondensation out;
  std::vector<double> schur(rank == 0 ? static_cast<std::size_t>(s) * static_cast<std::size_t>(s) : 0);

  const Stopwatch clock;
  MumpsInstance mumps(comm);
  DMUMPS_STRUC_C& id = mumps.id();
  mumps.icntl(18) = 3;  // the matrix distributed as each rank's entries
  mumps.icntl(19) = 1;  // the Schur complement, centralized on the host
  id.n = static_cast<MUMPS_INT>(model.dofs());
  id.nnz_loc = static_cast<MUMPS_INT8>(values.size());
  id.irn_loc = rows.data();
  id.jcn_loc = cols.data();
  id.a_loc = values.data();
  id.size_schur = s;
  id.listvar_schur = schur_variables.data();
  if (rank == 0) id.schur = schur.data();
  mumps.run(job_analyse_factorize, "the analysis and factorization of K with the ROI as Schur variables");
  out.factor_s = clock.seconds();
  out.factor_entries = id.infog[28] >= 0 ? static_cast<double>(id.infog[28]) : -1e6 * id.infog[28];  // <0: millions
  out.peak_megabytes = id.infog[20];
  if (rank == 0) {
    // For a symmetric matrix MUMPS returns the Schur complement's lower triangle by rows: the upper
    // triangle of this column-major array. The other triangle is not cleared (it held 655 to 2944
    // in norm on the paper brain, depending on what ran before), so it is never read.
    const Eigen::Map<const DenseMatrix> S(schur.data(), s, s);
    out.K_tilde = S.selfadjointView<Eigen::Upper>();
  }

  // The reduced right-hand sides, one per load pattern, from the patterns gathered on the host.
  const auto patterns = static_cast<MUMPS_INT>(model.loads.size());
  std::vector<double> rhs, reduced;
  std::vector<Vector> gathered;
  for (const auto& load : model.loads) {
    OwnedScatter scatter;
    OwnedVec whole;
    check(VecScatterCreateToZero(load.pattern.get(), scatter.out(), whole.out()), "VecScatterCreateToZero");
    check(VecScatterBegin(scatter.get(), load.pattern.get(), whole.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(scatter.get(), load.pattern.get(), whole.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    if (rank != 0) continue;
    const PetscScalar* w = nullptr;
    check(VecGetArrayRead(whole.get(), &w), "VecGetArrayRead");
    rhs.insert(rhs.end(), w, w + model.dofs());
    check(VecRestoreArrayRead(whole.get(), &w), "VecRestoreArrayRead");
  }
  if (patterns > 0) {
    if (rank == 0) {
      reduced.assign(static_cast<std::size_t>(s) * static_cast<std::size_t>(patterns), 0.0);
      id.rhs = rhs.data();
      id.redrhs = reduced.data();
    }
    id.nrhs = patterns;
    id.lrhs = id.n;
    id.lredrhs = s;
    mumps.icntl(20) = 0;  // dense right-hand sides on the host
    mumps.icntl(26) = 1;  // reduce them onto the Schur variables
    mumps.run(job_solve, "the reduction of the load patterns onto the ROI");
  }
  if (rank != 0) return out;
  for (MUMPS_INT k = 0; k < patterns; ++k)
    out.f_tilde.emplace_back(
        Eigen::Map<const Vector>(reduced.data() + static_cast<std::size_t>(k) * static_cast<std::size_t>(s), s));
  return out;
}

}  // namespace roifem::distributed
