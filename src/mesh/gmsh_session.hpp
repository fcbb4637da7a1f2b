// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// RAII around the Gmsh API. Gmsh keeps one global model per process, so at most one session
/// may be alive at a time (a second throws). Gmsh 4.8 reports errors by throwing std::string;
/// gmsh_call() turns them into InputError with context. Gmsh sets OpenMP's thread count to its own
/// General.NumThreads (1 unless set) when it starts; the session gives the process back the count
/// it found when it ends (without that, every OpenMP loop after a mesh was read ran on one thread).
#include <string>
#include <utility>

#include "common/errors.hpp"

namespace roifem::mesh {

class GmshSession {
 public:
  explicit GmshSession(bool verbose = false);
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
  ~GmshSession();

 private:
  int openmp_threads_;  ///< OpenMP's thread count before Gmsh started
};

/// Runs f(); a std::string thrown by Gmsh becomes InputError("<context>: <message>").
template <class F>
decltype(auto) gmsh_call(const std::string& context, F&& f) {
  try {
    return std::forward<F>(f)();
  } catch (const std::string& message) {
    throw InputError(context + ": " + message);
  }
}

}  // namespace roifem::mesh
