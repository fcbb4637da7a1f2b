// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/gmsh_session.hpp"

#include <gmsh.h>
#include <omp.h>

#include <atomic>

namespace roifem::mesh {

namespace {
std::atomic<bool> session_alive{false};  // Gmsh's own state is global; this only guards it.
}

GmshSession::GmshSession(bool verbose) : openmp_threads_(omp_get_max_threads()) {
  if (session_alive.exchange(true)) throw Error("internal: a second Gmsh session was opened while one is alive");
  gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
  gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
  gmsh::option::setNumber("General.Verbosity", verbose ? 4 : 1);
}

GmshSession::~GmshSession() {
  try {
    gmsh::finalize();
  } catch (...) {  // never throw from a destructor
  }
  omp_set_num_threads(openmp_threads_);
  session_alive = false;
}

}  // namespace roifem::mesh
