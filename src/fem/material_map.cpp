// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/material_map.hpp"

#include <limits>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::fem {

MaterialMap::MaterialMap(const Material& uniform) : materials_{uniform} {}

MaterialMap::MaterialMap(const mesh::TetMesh& mesh, const Material& base, const std::vector<RegionMaterial>& regions)
    : materials_{base} {
  if (regions.empty()) return;
  if (regions.size() >= std::numeric_limits<std::uint16_t>::max())
    throw InputError(mesh.source + ": too many material regions (" + std::to_string(regions.size()) + ")");
  index_.assign(mesh.tets.size(), 0);
  for (const RegionMaterial& region : regions) {
    const mesh::NamedSet& set = mesh.set(region.set);  // InputError listing the sets if missing
    if (set.dim != 3)
      throw InputError(mesh.source + ": material region '" + region.set + "' is a " + std::to_string(set.dim) +
                       "D set; a material needs a volume (3D) set such as grey_matter or white_matter");
    if (set.tets.empty()) throw InputError(mesh.source + ": material region '" + region.set + "' has no tetrahedra");
    region.material.validate();
    if (region.material.alpha != base.alpha)
      throw InputError("material region '" + region.set + "': alpha_per_s = " + number_text(region.material.alpha) +
                       " differs from the brain's " + number_text(base.alpha) +
                       "; one damping rate holds for the whole brain (C = alpha M), give it in [material]");
    materials_.push_back(region.material);
    const auto k = static_cast<std::uint16_t>(materials_.size() - 1);
    for (int e : set.tets) index_[static_cast<std::size_t>(e)] = k;
  }
}

std::vector<Index> MaterialMap::counts(Index num_tets) const {
  std::vector<Index> count(materials_.size(), 0);
  if (index_.empty()) {
    count[0] = num_tets;
    return count;
  }
  for (std::uint16_t k : index_) ++count[k];
  return count;
}

}  // namespace roifem::fem
