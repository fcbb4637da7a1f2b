// SPDX-License-Identifier: GPL-3.0-or-later
#include "simulation/run_checkpoint.hpp"

#include <string>

#include "common/errors.hpp"
#include "common/format.hpp"

namespace roifem::simulation {

namespace {

std::string group_of(long step) { return format("restart/step_%06ld", step); }

void write_vector(io::Hdf5Writer& h5, const std::string& name, const Vector& v) {
  h5.write(name, std::vector<double>(v.data(), v.data() + v.size()), {static_cast<hsize_t>(v.size())});
}

void write_numbers(io::Hdf5Writer& h5, const std::string& name, const std::vector<double>& numbers) {
  h5.write(name, numbers, {static_cast<hsize_t>(numbers.size())});
}

Vector read_vector(const io::Hdf5Reader& file, const std::string& name) {
  const std::vector<double> values = file.doubles(name);
  return Eigen::Map<const Vector>(values.data(), static_cast<Index>(values.size()));
}

}  // namespace

void write_checkpoint(io::Hdf5Writer& h5, const RunCheckpoint& c) {
  const std::string at = group_of(c.step);
  write_vector(h5, at + "/u", c.state.u);
  write_vector(h5, at + "/v", c.state.v);
  write_numbers(h5, at + "/t", {c.state.t});
  write_numbers(h5, at + "/ledger", c.ledger);
  write_numbers(h5, at + "/restarted_counters", c.restarted.counters());
  if (!c.integrator) return;
  write_numbers(h5, at + "/integrator_numbers", c.integrator->numbers);
  for (std::size_t i = 0; i < c.integrator->vectors.size(); ++i)
    write_vector(h5, at + "/integrator_vector_" + std::to_string(i), c.integrator->vectors[i]);
}

std::vector<long> checkpoint_steps(const io::Hdf5Reader& file) {
  std::vector<long> steps;
  for (const std::string& name : file.names("restart"))
    if (name.rfind("step_", 0) == 0) steps.push_back(std::stol(name.substr(5)));
  return steps;
}

RunCheckpoint read_checkpoint(const io::Hdf5Reader& file, long step) {
  const std::string at = group_of(step);
  if (!file.has(at)) {
    std::string have;
    for (const long k : checkpoint_steps(file)) have += (have.empty() ? "" : ", ") + std::to_string(k);
    throw InputError(file.path() + ": no restart point at step " + std::to_string(step) + " (it has " +
                     (have.empty() ? std::string("none: a run written before restarts, or with output.restart_every = 0 that did "
                                                 "not finish")
                                   : "steps " + have + ": every output.restart_every-th step and a finished run's last") +
                     ")");
  }
  RunCheckpoint c;
  c.step = step;
  c.state.u = read_vector(file, at + "/u");
  c.state.v = read_vector(file, at + "/v");
  const std::vector<double> t = file.doubles(at + "/t");
  if (t.size() != 1 || c.state.u.size() != c.state.v.size()) throw InputError(file.path() + ": /" + at + " is damaged");
  c.state.t = t[0];
  c.ledger = file.doubles(at + "/ledger");
  c.restarted = integrators::Stats::from_counters(file.doubles(at + "/restarted_counters"));
  if (!file.has(at + "/integrator_numbers")) return c;
  c.integrator.emplace();
  c.integrator->numbers = file.doubles(at + "/integrator_numbers");
  for (int i = 0; file.has(at + "/integrator_vector_" + std::to_string(i)); ++i)
    c.integrator->vectors.push_back(read_vector(file, at + "/integrator_vector_" + std::to_string(i)));
  return c;
}

}  // namespace roifem::simulation
