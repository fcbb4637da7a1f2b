#pragma once
/// Work that rank 0 does alone (writing files) inside collective code. A failure there must not
/// leave the other ranks waiting in the next collective call, nor rank 0 waiting in a collective
/// destructor while it unwinds (a MUMPS factor's): on_root tells every rank how the work went, and
/// every rank throws the same error, so all of them unwind together.
#include <mpi.h>

#include <exception>
#include <string>

#include "common/errors.hpp"

namespace roifem::distributed {

template <class Work>
void on_root(MPI_Comm comm, Work&& work) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string failure;
  int kind = 0;  // 0 none, 1 InputError, 2 other
  if (rank == 0) {
    try {
      work();
    } catch (const InputError& e) {
      failure = e.what();
      kind = 1;
    } catch (const std::exception& e) {
      failure = e.what();
      kind = 2;
    }
  }
  int length = static_cast<int>(failure.size());
  int header[2] = {kind, length};
  MPI_Bcast(header, 2, MPI_INT, 0, comm);
  if (header[0] == 0) return;
  failure.resize(static_cast<std::size_t>(header[1]));
  MPI_Bcast(failure.data(), header[1], MPI_CHAR, 0, comm);
  if (header[0] == 1) throw InputError(failure);
  throw Error(failure);
}

}  // namespace roifem::distributed
