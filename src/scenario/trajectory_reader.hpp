// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A tool's trajectory from a CSV file: a header `t_s,x_mm,y_mm,z_mm`, then one sample per line,
/// times strictly increasing from 0, the first sample (0, 0, 0, 0) (a tool starts where its nodes
/// are); the path runs piecewise linear through the samples and holds the last one.
#include <filesystem>
#include <string>
#include <string_view>

#include "model/tools.hpp"

namespace roifem::scenario {

/// InputError naming the file and line of a missing file, a wrong header, a malformed or
/// non-finite number, a time not after the previous one, a first sample other than zero, or fewer
/// than two samples.
model::ToolPath read_trajectory(const std::filesystem::path& file);
/// The same from the file's text (`source` names it in messages).
model::ToolPath parse_trajectory(std::string_view text, const std::string& source);

}  // namespace roifem::scenario
