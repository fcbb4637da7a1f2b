// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A scenario from a TOML table already in memory: what parse_scenario reads once the text is
/// parsed, and what a table built by a program (the Python module's dicts) goes through, with the
/// same strict checks. Messages name `source` (and file:line:column where the table has positions).
#include <toml++/toml.h>

#include <filesystem>
#include <string>

#include "scenario/scenario.hpp"

namespace roifem::scenario {

/// The text's TOML table: InputError "source:line:column: TOML syntax error: ..." otherwise (and for
/// text no TOML reader should be handed: scenario/toml_text_guard.hpp).
toml::table parse_scenario_table(std::string_view text, const std::string& source);
/// A scenario file's text; InputError naming the file when it cannot be opened.
std::string read_scenario_text(const std::filesystem::path& file);

Scenario scenario_from_table(const toml::table& root, const std::string& source, const std::filesystem::path& directory);

}  // namespace roifem::scenario
