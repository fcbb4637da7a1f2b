// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Error types. Every message names what is at fault: the file, element, node, parameter or step.
///  - InputError:  the user's input is wrong (file, scenario key, parameter value).
///  - ModelError:  the input is well-formed but the model it describes cannot be solved
///                 (no fixed nodes, a singular static part, an empty ROI).
///  - SolverError: a numerical method failed (factorization, divergence) at a named step / time.
#include <stdexcept>
#include <string>

namespace roifem {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
class InputError : public Error {
 public:
  using Error::Error;
};
class ModelError : public Error {
 public:
  using Error::Error;
};
class SolverError : public Error {
 public:
  using Error::Error;
};
/// A run stopped at the wall-clock limit its caller set (Integrator::set_time_limit: compare's and
/// energy's --max-run-seconds), at the model time `t` it had reached.
class OverTime : public Error {
 public:
  OverTime(double model_time, const std::string& what) : Error(what), t(model_time) {}
  double t;
};
/// A run stopped on SIGINT or SIGTERM between two steps (see simulation/interrupt.hpp).
class Interrupted : public Error {
 public:
  Interrupted(int signal_number, const std::string& what) : Error(what), signal(signal_number) {}
  int signal;
};

}  // namespace roifem
