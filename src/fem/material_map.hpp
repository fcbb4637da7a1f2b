// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The material of every tetrahedron: a brain with regions (grey and white matter, CSF) is
/// assembled element by element with its own lambda, mu and rho. One damping rate alpha holds for
/// the whole brain, so C = alpha M stays proportional to the mass (the modal reference, the
/// reductions and every integrator rely on that); a region that asks for another alpha is refused.
#include <cstdint>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "fem/material.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::fem {

/// A named volume set (3D) and the material its tetrahedra take.
struct RegionMaterial {
  std::string set;
  Material material;
  std::string name;  ///< preset or "custom", for reports
};

class MaterialMap {
 public:
  MaterialMap() : MaterialMap(Material{}) {}
  /// One material everywhere.
  explicit MaterialMap(const Material& uniform);
  /// `base` everywhere, then each region's material on its set's tetrahedra, in order (a later
  /// region wins where two overlap). Throws InputError naming the set for a missing or 2D set,
  /// or a region whose alpha differs from the base's.
  MaterialMap(const mesh::TetMesh& mesh, const Material& base, const std::vector<RegionMaterial>& regions);

  const Material& of(Index tet) const { return materials_[index_.empty() ? 0 : index_[static_cast<std::size_t>(tet)]]; }
  /// Which of materials() tetrahedron `tet` takes.
  std::size_t index_of(Index tet) const { return index_.empty() ? 0 : index_[static_cast<std::size_t>(tet)]; }
  const Material& base() const { return materials_.front(); }
  bool uniform() const { return index_.empty(); }
  double alpha() const { return materials_.front().alpha; }
  /// Whether some tetrahedron's law is not the linear one (fem/material_model.hpp).
  bool nonlinear() const {
    for (const Material& m : materials_)
      if (m.model != MaterialModel::linear) return true;
    return false;
  }
  /// Tetrahedra per material (index 0: the base), for reports.
  std::vector<Index> counts(Index num_tets) const;
  const std::vector<Material>& materials() const { return materials_; }
  /// The same regions with f applied to every material.
  template <class F>
  MaterialMap mapped(F f) const {
    MaterialMap copy = *this;
    for (Material& m : copy.materials_) m = f(m);
    return copy;
  }

 private:
  std::vector<Material> materials_;   ///< [0]: the base
  std::vector<std::uint16_t> index_;  ///< per tetrahedron; empty: all the base
};

}  // namespace roifem::fem
