// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A simulation scenario: plain data with defaults, read strictly from TOML (read_scenario).
/// Lengths in the file are millimetres, everything else SI; see scenarios/README.md for the keys.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "condensation/reduction.hpp"
#include "cutting/blade.hpp"
#include "fem/element.hpp"
#include "fem/material.hpp"
#include "fem/material_map.hpp"
#include "model/fem_model.hpp"
#include "roi/roi.hpp"

namespace roifem::scenario {

struct Scenario {
  std::filesystem::path file;           ///< where it was read from
  std::filesystem::path mesh;           ///< resolved against the scenario's directory
  std::string material_name = "paper";  ///< preset, or "custom"
  fem::Material material;
  /// [[material_region]]: named volume sets with their own material (in order; a later one wins)
  std::vector<fem::RegionMaterial> material_regions;
  fem::Element element = fem::Element::tet4;  ///< top-level `element`: tet4, nodal-pressure or tet10
  std::vector<std::string> fixed_sets{"base"};
  std::vector<model::SetLoad> loads;
  std::vector<model::SetTool> tools;  ///< [[tool]]: attached nodes follow a prescribed path
  std::vector<cutting::Blade> cuts;   ///< [[cut]]: blades that remove the tetrahedra they cross, or split along faces
  std::optional<roi::RoiSpec> roi;    ///< none: the full dynamic model
  condensation::Reduction reduction;  ///< of the static part, with an ROI
  std::string integrator = "trapezoid";
  std::string integrator_where;                ///< "file:line:column" of [time] integrator, for messages (empty: the default)
  double dt = 0.05;                            ///< s: the step, or with rtol the output interval (and first step)
  static constexpr double smallest_dt = 1e-9;  ///< s: below, a step is round-off (1e-300 gave "reciprocal condition nan")
  long steps = 200;
  std::optional<double> rtol;  ///< set: error-controlled steps (adaptive integrators), relative tolerance
  std::optional<double> atol;  ///< m (and m/s); default rtol x 1 mm
  /// The absolute tolerance in force: atol, or rtol x 1 mm.
  double absolute_tolerance() const { return atol.value_or(rtol.value_or(0) * 1e-3); }
  long field_every = 10;  ///< full displacement field every k steps (0: none)
  /// [output] restart_every: a restart point every k steps (0: only a finished run's last); not
  /// given: every 10th field (restart_interval()).
  std::optional<long> restart_every;
  long restart_interval() const { return restart_every.value_or(10 * field_every); }
  /// [haptic]: the haptic loop's settings (`roifem serve`), where the file gives them: its rate (Hz,
  /// default 1 kHz) and a neo-Hookean model's modified-Newton iterations per tick (default 2).
  std::optional<double> haptic_rate_hz;
  std::optional<int> haptic_newton_iterations;
  /// [restart]: go on from a restart point of an earlier run of this scenario (`roifem run --from
  /// FILE --step K` sets the same): its results file and step (none: the last point it holds).
  struct Restart {
    std::filesystem::path from;
    std::optional<long> step;
    std::string where;  ///< "file:line:column" of the table, for messages (empty: the command line)
  };
  std::optional<Restart> restart;
  /// The scenario as resolved (defaults filled in), as TOML text: stored with the results. Without
  /// [restart]: a restarted run stores the scenario of the run it goes on.
  std::string resolved_toml() const;
};

/// InputError naming the scenario's first [[cut]], or its [restart], when it has one: `command`
/// (e.g. "roifem energy") measures the uncut model from rest, and either left out without a word
/// would be a silent wrong answer. `roifem run` takes both.
void refuse_run_only_tables(const Scenario& scenario, std::string_view command);

/// Reads and checks a scenario. Throws InputError naming the file, line, table and key for syntax
/// errors, unknown keys, wrong types, missing required keys and non-finite or out-of-range values.
Scenario read_scenario(const std::filesystem::path& file);
/// The same from text (`source` names it in messages; relative paths resolve against `directory`).
Scenario parse_scenario(std::string_view text, const std::string& source, const std::filesystem::path& directory);

}  // namespace roifem::scenario
