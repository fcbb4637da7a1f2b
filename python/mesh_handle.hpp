// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// roifem.Mesh: a share of a TetMesh (its own, or aliasing a simulation's model, which it keeps alive).
#include <memory>

#include "mesh/tet_mesh.hpp"

namespace roifem::python {

struct Mesh {
  std::shared_ptr<const mesh::TetMesh> mesh;
};

}  // namespace roifem::python
