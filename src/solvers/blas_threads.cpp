// SPDX-License-Identifier: GPL-3.0-or-later
#include "solvers/blas_threads.hpp"

#include <dlfcn.h>

namespace roifem::solvers {
namespace {

struct OpenBlasThreads {
  using Set = void (*)(int);
  using Get = int (*)();
  Set set = nullptr;
  Get get = nullptr;
};

// Resolved once and never changed: which BLAS the process loaded does not change while it runs.
const OpenBlasThreads& open_blas() {
  static const OpenBlasThreads found = [] {
    OpenBlasThreads f;
    f.set = reinterpret_cast<OpenBlasThreads::Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    f.get = reinterpret_cast<OpenBlasThreads::Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    if (!f.set || !f.get) f = {};
    return f;
  }();
  return found;
}

}  // namespace

BlasThreadsScope::BlasThreadsScope(int threads) {
  const auto& blas = open_blas();
  if (threads == unchanged || !blas.set) return;
  const int now = blas.get();
  if (now == threads) return;
  previous_ = now;
  blas.set(threads);
}

BlasThreadsScope::~BlasThreadsScope() {
  const auto& blas = open_blas();
  if (previous_ > 0 && blas.set) blas.set(previous_);
}

bool BlasThreadsScope::controllable() { return open_blas().set != nullptr; }

int BlasThreadsScope::current() {
  const auto& blas = open_blas();
  return blas.get ? blas.get() : 1;
}

}  // namespace roifem::solvers
