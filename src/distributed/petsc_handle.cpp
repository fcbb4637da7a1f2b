#include "distributed/petsc_handle.hpp"

#include <string>

#include "common/errors.hpp"

namespace roifem::distributed {

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw SolverError(std::string("PETSc: ") + what + " failed (PETSc error " + std::to_string(static_cast<int>(code)) + ": " +
                    (text ? text : "unknown") + ")");
}

PetscSession::PetscSession(int argc, char** argv) : argc_(argc), argv_(argv) {
  check(PetscInitialize(&argc_, &argv_, nullptr, nullptr), "PetscInitialize");
}

PetscSession::~PetscSession() { PetscFinalize(); }

int PetscSession::rank() const {
  int r = 0;
  MPI_Comm_rank(comm(), &r);
  return r;
}

int PetscSession::size() const {
  int s = 1;
  MPI_Comm_size(comm(), &s);
  return s;
}

}  // namespace roifem::distributed
