// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/stats.hpp"

#include <array>

#include "common/errors.hpp"

namespace roifem::integrators {

namespace {

const std::array<StatsField, 10> fields{{
    {"steps", "steps taken", &Stats::steps},
    {"rhs_evals", "right-hand side (or residual) evaluations", &Stats::rhs_evals},
    {"jac_evals", "Jacobian evaluations", &Stats::jac_evals},
    {"lin_setups", "linear-solver setups (factorizations)", &Stats::lin_setups},
    {"lin_solves", "linear solves", &Stats::lin_solves},
    {"failed_steps", "steps failed and retried (an error test, Newton, an inverted element)", &Stats::failed_steps},
    {"lin_iterations", "iterations of an iterative linear solver (trapezoid-cg)", &Stats::lin_iterations},
    {"nonlinear_iterations", "Newton iterations on a nonlinear system", &Stats::nonlinear_iterations},
    {"indefinite_steps", "steps whose Newton matrix was indefinite (solved by LU)", &Stats::indefinite_steps},
    {"system_changes", "changes of the system taken in place (cuts), without a restart", &Stats::system_changes},
}};

}  // namespace

std::span<const StatsField> stats_fields() { return fields; }

const StatsField& stats_field(std::string_view name) {
  for (const StatsField& f : fields)
    if (f.name == name) return f;
  std::string names;
  for (const StatsField& f : fields) names += (names.empty() ? "" : ", ") + std::string(f.name);
  throw Error("internal: no counter '" + std::string(name) + "' (the counters: " + names + ")");
}

Stats& Stats::operator+=(const Stats& o) {
  for (const StatsField& f : fields) this->*f.member += o.*f.member;
  factorization_s += o.factorization_s;
  return *this;
}

std::vector<double> Stats::counters() const {
  std::vector<double> numbers;
  numbers.reserve(fields.size());
  for (const StatsField& f : fields) numbers.push_back(static_cast<double>(this->*f.member));
  return numbers;
}

Stats Stats::from_counters(const std::vector<double>& numbers, std::size_t first) {
  if (numbers.size() < first + fields.size()) throw InputError("a checkpoint's counters are missing (a damaged file?)");
  Stats s;
  for (std::size_t i = 0; i < fields.size(); ++i) s.*fields[i].member = static_cast<long>(numbers[first + i]);
  return s;
}

std::string stats_line(const Stats& stats) {
  std::string line;
  for (const StatsField& f : fields) {
    const long value = stats.*f.member;
    if (value == 0 && f.name != "steps") continue;
    line += (line.empty() ? "" : " ") + std::string(f.name) + "=" + std::to_string(value);
  }
  return line;
}

}  // namespace roifem::integrators
