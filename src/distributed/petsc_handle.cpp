// SPDX-License-Identifier: GPL-3.0-or-later
#include "distributed/petsc_handle.hpp"

#include <string>

#include "common/errors.hpp"
#include "distributed/root_work.hpp"

namespace roifem::distributed {

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw SolverError(std::string("PETSc: ") + what + " failed (PETSc error " + std::to_string(static_cast<int>(code)) + ": " +
                    (text ? text : "unknown") + ")");
}

void check_options_used(const char* after) {
  PetscInt count = 0;
  char** names = nullptr;
  char** values = nullptr;
  check(PetscOptionsLeftGet(nullptr, &count, &names, &values), "PetscOptionsLeftGet");
  std::string unused;
  for (PetscInt i = 0; i < count; ++i)
    unused += std::string(unused.empty() ? "" : ", ") + "-" + names[i] + (values[i] ? std::string(" ") + values[i] : "");
  check(PetscOptionsLeftRestore(nullptr, &count, &names, &values), "PetscOptionsLeftRestore");  // zeroes count
  if (!unused.empty())
    throw Agreed<InputError>("PETSc options that nothing read " + std::string(after) + ": " + unused +
                             " (misspelt, or not for this command; `-help` after -- lists the ones each solver reads)");
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
