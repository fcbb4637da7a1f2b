// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// roifem.Scenario: a scenario with the TOML table it was read from, so that overrides apply to
/// what the user wrote (exactly: no number goes through text again) and the result is checked anew.
#include <toml++/toml.h>

#include <filesystem>
#include <string>

#include "bindings.hpp"
#include "scenario/scenario.hpp"

namespace roifem::python {

struct ScenarioHandle {
  scenario::Scenario scenario;
  toml::table table;
  std::string source;               ///< names it in messages: the file, or "<dict>"
  std::filesystem::path directory;  ///< relative paths resolve against it
};

/// The same scenario with `overrides` applied: a dict merges into the table of its name, None
/// removes the key, anything else replaces it. InputError for a key or value the reader refuses.
ScenarioHandle with_overrides(const ScenarioHandle& base, const py::dict& overrides);
/// A roifem.Scenario, or a scenario file's path.
ScenarioHandle scenario_handle_of(py::handle scenario_or_file);

}  // namespace roifem::python
