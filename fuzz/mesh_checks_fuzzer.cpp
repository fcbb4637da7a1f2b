// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer harness: a small tetrahedral mesh decoded from the bytes (node count, raw double
// coordinates, NaN and infinity included, raw int32 node indices), then the mesh checks. They may
// only answer with roifem::Error; a mesh that passes must give finite statistics.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "common/errors.hpp"
#include "mesh/mesh_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int nodes = 1 + data[0] % 16;
  std::size_t at = 1;
  roifem::mesh::TetMesh mesh;
  mesh.nodes.resize(3, nodes);
  for (int n = 0; n < nodes; ++n)
    for (int c = 0; c < 3; ++c) {
      double x = 0;
      if (at + sizeof x <= size) std::memcpy(&x, data + at, sizeof x);
      at += sizeof x;
      mesh.nodes(c, n) = x;
    }
  while (at + 4 * sizeof(std::int32_t) <= size) {
    roifem::mesh::Tet t{};
    for (int& v : t) {
      std::int32_t raw = 0;
      std::memcpy(&raw, data + at, sizeof raw);
      at += sizeof raw;
      v = raw;
    }
    mesh.tets.push_back(t);
  }
  try {
    roifem::mesh::check_mesh(mesh);
    const auto stats = roifem::mesh::mesh_statistics(mesh);
    if (!std::isfinite(stats.volume) || !(stats.quality_min > 0)) std::abort();  // passed the checks: must be sound
    (void)roifem::mesh::boundary_faces(mesh);
  } catch (const roifem::Error&) {
  }
  return 0;
}
