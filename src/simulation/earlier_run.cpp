// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/earlier_run.hpp"

#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"

namespace roifem::simulation {

namespace {

/// A line of a resolved scenario as compared: a file's path (mesh, trajectory) made canonical, so
/// that the same file named two ways (scenarios/../meshes, meshes) agrees.
std::string compared(const std::string& line) {
  for (const char* key : {"mesh = \"", "trajectory = \""}) {
    if (line.rfind(key, 0) != 0 || line.back() != '"') continue;
    const std::size_t start = std::string(key).size();
    const std::filesystem::path path = line.substr(start, line.size() - start - 1);
    return std::string(key) + std::filesystem::weakly_canonical(path).string() + "\"";
  }
  return line;
}

/// The lines of a resolved scenario that must agree: all but the run's length and its integrator
/// (another goes on afresh from the state).
std::vector<std::string> compared_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("steps = ", 0) != 0 && line.rfind("integrator = ", 0) != 0 && line.rfind("rtol = ", 0) != 0 &&
        line.rfind("atol = ", 0) != 0)
      lines.push_back(compared(line));
  return lines;
}

}  // namespace

EarlierRun::EarlierRun(const std::filesystem::path& file, const scenario::Scenario& scenario) : file_(file) {
  const std::string stored = file_.text("scenario");
  if (stored.empty() || !file_.has("time_s"))
    throw InputError(file_.path() + ": not the results file of a `roifem run` (no scenario or time_s in it)");
  const std::vector<std::string> was = compared_lines(stored), is = compared_lines(scenario.resolved_toml());
  for (std::size_t i = 0; i < std::max(was.size(), is.size()); ++i) {
    const std::string a = i < was.size() ? was[i] : "(nothing)", b = i < is.size() ? is[i] : "(nothing)";
    if (a != b)
      throw InputError(
          format("%s: a restart goes on the run of the same scenario (its steps and integrator apart), and %s was "
                 "run with another: its resolved scenario's line %zu is '%s', this one's '%s'",
                 scenario.file.string().c_str(), file_.path().c_str(), i + 1, a.c_str(), b.c_str()));
  }
}

RunCheckpoint EarlierRun::checkpoint(std::optional<long> step) const {
  if (!step) {
    const std::vector<long> steps = checkpoint_steps(file_);
    if (steps.empty())
      throw InputError(file_.path() +
                       ": holds no restart point (a run written before restarts, or with output.restart_every "
                       "= 0 that did not finish)");
    step = steps.back();
  }
  return read_checkpoint(file_, *step);
}

const double* EarlierRun::row(const std::string& name, long k) const {
  auto it = series_.find(name);
  if (it == series_.end()) {
    Series s;
    if (file_.has(name)) {
      std::vector<hsize_t> shape;
      s.values = file_.doubles(name, &shape);
      for (std::size_t d = 1; d < shape.size(); ++d) s.record *= shape[d];
    }
    it = series_.emplace(name, std::move(s)).first;
  }
  const Series& s = it->second;
  if (s.values.empty()) return nullptr;
  if (static_cast<std::size_t>(k + 1) * s.record > s.values.size())
    throw InputError(
        format("%s: /%s holds %zu steps, not step %ld", file_.path().c_str(), name.c_str(), s.values.size() / s.record, k));
  return s.values.data() + static_cast<std::size_t>(k) * s.record;
}

bool EarlierRun::has_field(long k) const { return file_.has(format("fields/displacement_mm_%06ld", k)); }

std::vector<double> EarlierRun::field(long k) const { return file_.doubles(format("fields/displacement_mm_%06ld", k)); }

}  // namespace roifem::simulation
