// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/scalpel.hpp"

#include <algorithm>

namespace roifem::serve {

cutting::Blade scalpel_blade(const std::string& name, const Vec3& edge_from_mm, const Vec3& edge_to_mm, const Vec3& move_mm,
                             double start_s, double duration_s) {
  cutting::Blade blade;
  blade.name = name;
  blade.mode = cutting::CutMode::remove;
  blade.edge_a = edge_from_mm * mm;
  blade.edge_b = edge_to_mm * mm;
  blade.start = start_s;
  blade.path.displacement = move_mm * mm;
  blade.path.ramp.duration = duration_s;
  blade.where = "the page's scalpel";
  return blade;
}

std::vector<Index> crossed_tetrahedra(const cutting::Blade& blade, const mesh::TetMesh& mesh) {
  std::vector<Index> elements;
  for (const cutting::Crossing& c : cutting::swept_elements(blade, mesh)) elements.push_back(c.element);
  std::sort(elements.begin(), elements.end());
  return elements;
}

}  // namespace roifem::serve
