// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Failures across ranks. One rank's failure inside collective code must not leave the others
/// waiting in the next collective call (nor rank 0 waiting in a collective destructor while it
/// unwinds: a MUMPS factor's). Two kinds:
///  - agreed: every rank knows of it at the same point and throws alike (Agreed<E>), so all of them
///    unwind together and the program reports it once, on rank 0, with no MPI_Abort: work rank 0
///    does alone (on_root: it tells every rank how it went), checks every rank makes alike
///    (on_every_rank), a signal every rank has heard of (agreed_signal);
///  - any other: the rank that failed names itself and aborts the job (roifem-mpi's main).
#include <mpi.h>

#include <exception>
#include <string>

#include "common/errors.hpp"

namespace roifem::distributed {

/// Marks an error that every rank threw together.
class AgreedByEveryRank {
 public:
  virtual ~AgreedByEveryRank() = default;
};
template <class E>
class Agreed : public E, public AgreedByEveryRank {
 public:
  using E::E;
};

namespace detail {

/// 0: none, 1: InputError, 2: any other error.
template <class Work>
int failure_of(Work&& work, std::string& failure) {
  try {
    work();
  } catch (const InputError& e) {
    failure = e.what();
    return 1;
  } catch (const std::exception& e) {
    failure = e.what();
    return 2;
  }
  return 0;
}

[[noreturn]] inline void throw_agreed(int kind, const std::string& failure) {
  if (kind == 1) throw Agreed<InputError>(failure);
  throw Agreed<Error>(failure);
}

}  // namespace detail

/// `work` on rank 0 alone; every rank throws its failure (Agreed).
template <class Work>
void on_root(MPI_Comm comm, Work&& work) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string failure;
  const int kind = rank == 0 ? detail::failure_of(work, failure) : 0;
  int header[2] = {kind, static_cast<int>(failure.size())};
  MPI_Bcast(header, 2, MPI_INT, 0, comm);
  if (header[0] == 0) return;
  failure.resize(static_cast<std::size_t>(header[1]));
  MPI_Bcast(failure.data(), header[1], MPI_CHAR, 0, comm);
  detail::throw_agreed(header[0], failure);
}

/// `work` on every rank (reading and checking the same input): when every rank fails, each throws
/// its own failure as Agreed; when only some do, those throw theirs plainly (main aborts the job)
/// and the others an Agreed error saying so.
template <class Work>
void on_every_rank(MPI_Comm comm, Work&& work) {
  std::string failure;
  const int kind = detail::failure_of(work, failure);
  int failed = kind != 0, all = 0, any = 0;
  MPI_Allreduce(&failed, &all, 1, MPI_INT, MPI_MIN, comm);
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, comm);
  if (all != 0) detail::throw_agreed(kind, failure);
  if (kind == 1) throw InputError(failure);
  if (kind != 0) throw Error(failure);
  if (any != 0) throw Agreed<Error>("another rank failed (its message follows)");
}

/// The largest signal number any rank has received (0: none): after it, every rank stops together.
inline int agreed_signal(MPI_Comm comm, int mine) {
  int largest = 0;
  MPI_Allreduce(&mine, &largest, 1, MPI_INT, MPI_MAX, comm);
  return largest;
}

}  // namespace roifem::distributed
