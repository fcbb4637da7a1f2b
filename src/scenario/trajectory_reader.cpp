// SPDX-License-Identifier: GPL-3.0-or-later
#include "scenario/trajectory_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::scenario {

namespace {

constexpr const char* header = "t_s,x_mm,y_mm,z_mm";

[[noreturn]] void refuse(const std::string& where, const std::string& what) { throw InputError(where + ": " + what); }

/// The four numbers of a line, or InputError naming it.
std::array<double, 4> sample(const std::string& line, const std::string& where) {
  std::array<double, 4> x{};
  std::istringstream in(line);
  for (std::size_t i = 0; i < 4; ++i) {
    std::string field;
    if (!std::getline(in, field, i < 3 ? ',' : '\n'))
      refuse(where, "expected four numbers t_s, x_mm, y_mm, z_mm, got '" + line + "'");
    std::size_t used = 0;
    try {
      x[i] = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || field.find_first_not_of(" \t\r", used) != std::string::npos)
      refuse(where, "'" + field + "' is not a number (expected t_s, x_mm, y_mm, z_mm)");
    if (!std::isfinite(x[i])) refuse(where, "'" + field + "' is not finite");
  }
  std::string rest;
  if (std::getline(in, rest) && rest.find_first_not_of(" \t\r") != std::string::npos)
    throw InputError(where + ": more than four fields");
  return x;
}

}  // namespace

model::ToolPath read_trajectory(const std::filesystem::path& file) {
  if (std::filesystem::is_directory(file))
    throw InputError(file.string() + ": is a directory, not a trajectory file (CSV: t_s,x_mm,y_mm,z_mm)");
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot open trajectory file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_trajectory(text.str(), file.string());
}

model::ToolPath parse_trajectory(std::string_view text, const std::string& source) {
  std::istringstream in{std::string(text)};
  std::string line;
  long number = 0;
  auto where = [&] { return source + ":" + std::to_string(number); };
  if (!std::getline(in, line) || (++number, line.substr(0, line.find_last_not_of(" \t\r") + 1) != header))
    throw InputError(source + ":1: a trajectory starts with the header '" + std::string(header) + "'");
  auto samples = std::array<std::shared_ptr<model::Ramp::Samples>, 3>{};
  for (auto& s : samples) s = std::make_shared<model::Ramp::Samples>();
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto x = sample(line, where());
    const std::vector<double>& times = samples[0]->t;
    if (times.empty() && (x[0] != 0 || x[1] != 0 || x[2] != 0 || x[3] != 0))
      throw InputError(where() + ": the first sample must be 0, 0, 0, 0 (a tool starts at rest where its nodes are)");
    if (!times.empty() && !(x[0] > times.back()))
      throw InputError(where() + ": t = " + number_text(x[0]) + " s is not after the previous sample's " +
                       number_text(times.back()) + " s (times must increase)");
    for (std::size_t c = 0; c < 3; ++c) {
      samples[c]->t.push_back(x[0]);
      samples[c]->value.push_back(x[c + 1] * mm);
    }
  }
  if (samples[0]->t.size() < 2) throw InputError(source + ": a trajectory needs two or more samples");
  model::ToolPath path;
  path.trajectory.emplace();
  for (std::size_t c = 0; c < 3; ++c) (*path.trajectory)[c] = model::Ramp::sampled(samples[c]);
  path.displacement = path.at(samples[0]->t.back());
  path.ramp.duration = samples[0]->t.back();
  path.trajectory_file = source;
  return path;
}

}  // namespace roifem::scenario
