// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/box_mesh.hpp"

#include <gmsh.h>

#include <algorithm>

#include "mesh/gmsh_reader.hpp"
#include "mesh/gmsh_session.hpp"

namespace roifem::mesh {

namespace {
/// Names the six faces (nodes and boundary triangles) by position, tolerance relative to the box size.
void name_faces(TetMesh& mesh, double lx, double ly, double lz) {
  const double extent[3] = {lx, ly, lz};
  const std::vector<Triangle> boundary = boundary_faces(mesh);
  const char* names[3][2] = {{"x0", "x1"}, {"y0", "y1"}, {"z0", "z1"}};
  for (int c = 0; c < 3; ++c)
    for (int side = 0; side < 2; ++side) {
      NamedSet& set = mesh.sets[names[c][side]];
      set.dim = 2;
      set.nodes.clear();
      const double plane = side * extent[c], tol = 1e-9 * extent[c];
      for (int i = 0; i < mesh.num_nodes(); ++i)
        if (std::abs(mesh.nodes(c, i) - plane) <= tol) set.nodes.push_back(i);
      set.triangles.clear();
      for (const Triangle& f : boundary)
        if (std::all_of(f.begin(), f.end(), [&](int n) { return std::abs(mesh.nodes(c, n) - plane) <= tol; }))
          set.triangles.push_back(f);
    }
  NamedSet& box = mesh.sets["box"];
  box.dim = 3;
  box.nodes.resize(static_cast<std::size_t>(mesh.num_nodes()));
  for (int i = 0; i < mesh.num_nodes(); ++i) box.nodes[static_cast<std::size_t>(i)] = i;
  box.tets.resize(mesh.tets.size());
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) box.tets[e] = static_cast<int>(e);
}
}  // namespace

TetMesh structured_box_mesh(int nx, int ny, int nz, double lx, double ly, double lz) {
  TetMesh mesh;
  mesh.source = "<structured box>";
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  mesh.nodes.resize(3, (nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) mesh.nodes.col(id(i, j, k)) = Vec3(lx * i / nx, ly * j / ny, lz * k / nz);
  // The six paths from corner 0 to corner 7 along the cube's edges; each gives one tetrahedron.
  const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : paths) {
          int c[3] = {i, j, k};
          Tet t{};
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[static_cast<std::size_t>(s) + 1] = id(c[0], c[1], c[2]);
          }
          mesh.tets.push_back(t);
          if (signed_volume(mesh, mesh.num_tets() - 1) < 0) std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
        }
  name_faces(mesh, lx, ly, lz);
  return mesh;
}

TetMesh unstructured_box_mesh(double lx, double ly, double lz, double h) {
  GmshSession session;
  return gmsh_call("box mesh generation", [&] {
    gmsh::model::add("box");
    gmsh::model::occ::addBox(0, 0, 0, lx, ly, lz);
    gmsh::model::occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", h);
    gmsh::option::setNumber("Mesh.MeshSizeMin", h);
    gmsh::model::mesh::generate(3);
    TetMesh mesh = extract_tet_mesh("<unstructured box>", 1.0);
    name_faces(mesh, lx, ly, lz);
    return mesh;
  });
}

}  // namespace roifem::mesh
