#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# mpirun with what this project's machines need: Open MPI refuses to run as root unless told (CI
# and these machines run as root), and a 2-core machine counts fewer slots than ranks asked for.
# usage: scripts/mpirun.sh -n P PROGRAM ARGS...   (as mpirun; roifem-mpi is looked up in the
# Release build when it is not on PATH)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
here=$(cd "$(dirname "$0")/.." && pwd)
if ! command -v roifem-mpi > /dev/null 2>&1 && [ -x "$here/build/release/src/app/roifem-mpi" ]; then
  PATH="$here/build/release/src/app:$PATH"
  export PATH
fi
exec mpirun --oversubscribe "$@"
