// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// RAII over PETSc: the session (PetscInitialize / PetscFinalize, MPI with it), owned objects
/// destroyed by their XDestroy, and error codes turned into exceptions. PETSc's own handler still
/// prints its traceback (file, line, call) on stderr; check() adds which of our steps failed.
#include <petscksp.h>

#include <utility>

namespace roifem::distributed {

/// Throws SolverError("PETSc: WHAT failed (PETSc error N: TEXT)") unless code is 0.
void check(PetscErrorCode code, const char* what);

/// Agreed<InputError> naming every option of PETSc's database that nothing has read: a misspelt
/// option (-ksp_typo) is otherwise ignored, and another solver runs than the one asked for. Call it
/// once every PETSc object of the command has read its options (`after` says which).
void check_options_used(const char* after);

/// An owned PETSc object (Vec, Mat, KSP, IS, ...): destroyed with Destroy, never copied.
template <class T, PetscErrorCode (*Destroy)(T*)>
class Owned {
 public:
  Owned() = default;
  Owned(Owned&& o) noexcept : object_(std::exchange(o.object_, nullptr)) {}
  Owned& operator=(Owned&& o) noexcept {
    std::swap(object_, o.object_);
    return *this;
  }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() { reset(); }
  T get() const { return object_; }
  /// For XCreate(..., handle.out()): releases what it held.
  T* out() {
    reset();
    return &object_;
  }
  void reset() {
    if (object_) Destroy(&object_);
    object_ = nullptr;
  }

 private:
  T object_ = nullptr;
};

using OwnedVec = Owned<Vec, VecDestroy>;
using OwnedMat = Owned<Mat, MatDestroy>;
using OwnedKsp = Owned<KSP, KSPDestroy>;
using OwnedIs = Owned<IS, ISDestroy>;
using OwnedScatter = Owned<VecScatter, VecScatterDestroy>;
using OwnedNullSpace = Owned<MatNullSpace, MatNullSpaceDestroy>;
using OwnedPartitioning = Owned<MatPartitioning, MatPartitioningDestroy>;

/// PETSc (and MPI) for the lifetime of the object; one per process. argv holds PETSc's options
/// ("-ksp_type cg -pc_type gamg"); the program's own options are parsed apart (roifem-mpi: after --).
class PetscSession {
 public:
  PetscSession(int argc, char** argv);
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;
  ~PetscSession();
  MPI_Comm comm() const { return PETSC_COMM_WORLD; }
  int rank() const;
  int size() const;

 private:
  int argc_;
  char** argv_;
};

}  // namespace roifem::distributed
