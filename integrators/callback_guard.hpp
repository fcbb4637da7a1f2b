#pragma once
/// C callbacks (SUNDIALS right-hand sides, residuals and Jacobians; GSL's) must not let a C++
/// exception cross the C library: the body runs here, an exception is stored for the owner to
/// rethrow after the C call returns, and the library gets its failure code (as deal.II's
/// SUNDIALS wrappers do).
#include <exception>

namespace roifem::integrators {

/// 0 when `body` returns, `failure` when it throws (the exception kept in `pending`).
template <class Body>
int guarded_callback(std::exception_ptr& pending, int failure, Body&& body) noexcept {
  try {
    body();
    return 0;
  } catch (...) {
    pending = std::current_exception();
    return failure;
  }
}

}  // namespace roifem::integrators
