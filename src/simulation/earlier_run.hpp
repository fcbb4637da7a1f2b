// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The results file of a run that a restart goes on (`roifem run --from FILE --step K`): its
/// scenario, its restart points, and what it recorded at each step, read back so that the
/// restarted run's results.h5 holds steps 0..K as the earlier run wrote them.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/hdf5_reader.hpp"
#include "scenario/scenario.hpp"
#include "simulation/run_checkpoint.hpp"

namespace roifem::simulation {

class EarlierRun {
 public:
  /// Opens `file` (InputError when it is missing, not a results file, or of another scenario:
  /// `scenario`'s resolved text must be the file's, its steps, integrator and tolerances apart,
  /// else the first line that differs is named).
  EarlierRun(const std::filesystem::path& file, const scenario::Scenario& scenario);
  const io::Hdf5Reader& file() const { return file_; }
  /// The integrator the run went with.
  std::string integrator() const { return file_.attribute("integrator"); }
  /// The restart point of `step`, or of the last step that has one (none given).
  RunCheckpoint checkpoint(std::optional<long> step) const;
  /// Row k of the per-step dataset `name` (prod of its record shape doubles), or nullptr when
  /// the run recorded no such series.
  const double* row(const std::string& name, long k) const;
  /// The displacement field of step k, when the run stored one.
  bool has_field(long k) const;
  std::vector<double> field(long k) const;

 private:
  struct Series {
    std::vector<double> values;
    std::size_t record = 1;  ///< doubles per row
  };
  io::Hdf5Reader file_;
  mutable std::map<std::string, Series> series_;
};

}  // namespace roifem::simulation
