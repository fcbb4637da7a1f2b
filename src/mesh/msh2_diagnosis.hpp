// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Gmsh 4.8 says only "Error loading 'FILE'" when an ASCII MSH 2 file is truncated or malformed.
/// After such a failure (never on the good path), this scan finds the first line at fault.
#include <filesystem>
#include <string>

namespace roifem::mesh {

/// For an ASCII MSH 2.x file: "LINE: what is wrong there" for the first malformed line of the
/// $Nodes or $Elements section, or the line where the file ends inside a section ("truncated");
/// an empty string when the file is not ASCII MSH 2 or no fault is found.
std::string diagnose_msh2_ascii(const std::filesystem::path& file);

}  // namespace roifem::mesh
