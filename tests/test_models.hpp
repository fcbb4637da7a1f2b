#pragma once
/// Models with known structure shared by the tests: the shipped brain as in the paper (base held,
/// the opening's walls pulled apart) and a small cantilever beam, each with its ROI partition.
#include <string>

#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/fem_model.hpp"
#include "roi/roi.hpp"

namespace roifem::test {

/// The shipped brain, base fixed, the opening's walls pulled apart by 1 mN each.
struct PaperBrain {
  mesh::TetMesh mesh = mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  model::FemModel model = model::build_fem_model(
      mesh, fem::material_preset("paper"), {"base"},
      {{"opening_left", Vec3(-1e-3, 0, 0), model::Ramp{0.5}}, {"opening_right", Vec3(1e-3, 0, 0), model::Ramp{0.5}}});
  const fem::DofMap& dofs() const { return *model.dofs; }
  roi::Partition partition(const roi::RoiSpec& spec) const {
    return roi::partition_dofs(model.system.K, *model.dofs, roi::select_roi_nodes(mesh, *model.dofs, spec));
  }
};

/// The paper's ROIs: the `count` free nodes nearest (0, 0, 40) mm.
inline roi::RoiSpec nearest(Index count) {
  return {.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0, 0, 0.040), .count = count, .set = {}};
}

/// A 60 x 20 x 20 mm beam held at x = 0, its far end pulled in z; the ROI is the 27 nodes at that end.
struct Beam {
  mesh::TetMesh mesh = mesh::structured_box_mesh(6, 2, 2, 0.06, 0.02, 0.02);
  model::FemModel model = model::build_fem_model(mesh, fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8), {"x0"},
                                                 {{"x1", Vec3(0, 0, 1e-3), model::Ramp{0.2}}});
  roi::Partition partition() const {
    const roi::RoiSpec spec{.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0.06, 0.01, 0.01), .count = 27, .set = {}};
    return roi::partition_dofs(model.system.K, *model.dofs, roi::select_roi_nodes(mesh, *model.dofs, spec));
  }
};

}  // namespace roifem::test
