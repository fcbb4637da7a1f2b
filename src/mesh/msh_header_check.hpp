// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A guard in front of Gmsh's MSH reader. Gmsh 4.8 sizes its arrays from the counts in the
/// $Nodes / $Elements headers before it reads a single entry, so a corrupt or hostile count
/// (999999999999 nodes in a 100-byte file) ends in std::bad_alloc or an hours-long read. Every
/// node and element takes at least a few bytes of the file, so a count above the file's size is
/// impossible and is refused here, naming the file, the section and both numbers.
#include <filesystem>

namespace roifem::mesh {

/// Throws InputError when a $Nodes or $Elements header of an MSH 2.2 or 4.1 file (ASCII, the
/// ASCII header lines of MSH 2.2 binary, or the 8-byte little-endian header of MSH 4.1 binary)
/// claims more entries than the file has bytes.
void check_msh_header_counts(const std::filesystem::path& file);

}  // namespace roifem::mesh
