// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The page's scalpel as a blade (cutting/blade.hpp): a stroke is the edge from `edge_from_mm` to
/// `edge_to_mm` swept straight by `move_mm`, the keys of a [[cut]] (scenario/README.md), so that a
/// replay states each stroke as the scenario reader builds it.
#include <string>
#include <vector>

#include "cutting/blade.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::serve {

/// The stroke's blade, starting at `start_s` and sweeping over `duration_s` (which leave the
/// tetrahedra it crosses as they are), as read_cut builds a [[cut]] with move_mm.
cutting::Blade scalpel_blade(const std::string& name, const Vec3& edge_from_mm, const Vec3& edge_to_mm, const Vec3& move_mm,
                             double start_s, double duration_s);
/// The tetrahedra of `mesh` the blade's swept surface crosses, ascending.
std::vector<Index> crossed_tetrahedra(const cutting::Blade& blade, const mesh::TetMesh& mesh);

}  // namespace roifem::serve
