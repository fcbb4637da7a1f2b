// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// RAII over SUNDIALS 6.4 C handles. The Context is declared first in every owner so that it is
/// destroyed last. Debian's SUNDIALS uses 64-bit sunindextype: CSC index arrays are in that type.
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "common/errors.hpp"
#include "common/types.hpp"
#include "integrators/sundials/vector_ops.hpp"

namespace roifem::integrators::sundials {

struct ContextDeleter {
  void operator()(SUNContext c) const { SUNContext_Free(&c); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};

/// The integrator memory of ARKStep (ARKStepFree) and of IDA (IDAFree).
struct ArkodeMemoryDeleter {
  void operator()(void* memory) const;
};
struct IdaMemoryDeleter {
  void operator()(void* memory) const;
};

using Context = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using ArkodeMemory = std::unique_ptr<void, ArkodeMemoryDeleter>;
using IdaMemory = std::unique_ptr<void, IdaMemoryDeleter>;

/// SUNDIALS prints its error messages to stderr; the integrators keep the last one instead
/// (ARKStepSetErrHandlerFn / IDASetErrHandlerFn) and put it into the exception they throw.
struct LastError {
  std::string message;
  static void handler(int, const char*, const char* function, char* msg, void* self) {
    static_cast<LastError*>(self)->message = std::string(function) + ": " + msg;
  }
  /// " (ARKODE: ...)" or "" when SUNDIALS said nothing.
  std::string detail() const { return message.empty() ? "" : " (" + message + ")"; }
};

inline Context make_context() {
  SUNContext c = nullptr;
  if (SUNContext_Create(nullptr, &c) != 0) throw SolverError("SUNDIALS: cannot create a context");
  return Context(c);
}

inline Vector make_vector(Index n, SUNContext ctx) {
  N_Vector v = N_VNew_Serial(static_cast<sunindextype>(n), ctx);
  if (!v) throw SolverError("SUNDIALS: cannot allocate a vector of " + std::to_string(n));
  use_vectorized_ops(v);
  return Vector(v);
}

/// A view of an N_Vector's data as an Eigen vector.
inline Eigen::Map<Eigen::VectorXd> view(N_Vector v) { return {N_VGetArrayPointer(v), static_cast<Index>(N_VGetLength(v))}; }

/// The name of a return flag from ARKStepGetReturnFlagName / IDAGetReturnFlagName, which
/// malloc the string they return: copied, and the original freed.
inline std::string flag_name(char* owned) {
  std::string name = owned ? owned : "unknown flag";
  std::free(owned);
  return name;
}

/// Throws SolverError "<what> failed (flag F)" when flag < 0.
inline void check(int flag, const std::string& what) {
  if (flag < 0) throw SolverError(what + " failed (flag " + std::to_string(flag) + ")");
}

/// Copies an Eigen CSC matrix into a SUNSparseMatrix (CSC, 64-bit indices).
Matrix make_sparse(const SparseMatrix& A, SUNContext ctx);
/// Overwrites `target` (allocated with A's non-zero count) with A: pattern and values. SUNDIALS
/// zeroes a sparse matrix, index arrays included, before it calls a Jacobian or mass function,
/// so copying the values alone would leave an empty matrix.
void copy_into(const SparseMatrix& A, SUNMatrix target);

}  // namespace roifem::integrators::sundials
