// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/msh_writer.hpp"

#include <gmsh.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

#include "common/atomic_file.hpp"
#include "mesh/gmsh_session.hpp"

namespace roifem::mesh {

namespace {

constexpr int msh_triangle = 2;
constexpr int msh_tet4 = 4;

using Signature = std::vector<std::string>;  // the names of the sets an element belongs to

/// Elements grouped by the sets they belong to: one discrete entity per group.
struct EntityPlan {
  std::map<Signature, std::vector<std::size_t>> members;  // signature -> element indices
};

std::size_t tag_of(int node) { return static_cast<std::size_t>(node) + 1; }

}  // namespace

void write_msh(const TetMesh& mesh, const std::filesystem::path& output, double length_unit) {
  // Tetrahedra: by the 3D sets that list them.
  std::vector<Signature> tet_sets(mesh.tets.size());
  // Triangles: every triangle of a 2D set, identified by its sorted nodes, in first-seen orientation.
  std::map<std::array<int, 3>, std::size_t> triangle_index;
  std::vector<Triangle> triangles;
  std::vector<Signature> triangle_sets;
  for (const auto& [name, set] : mesh.sets) {
    if (set.dim == 3)
      for (int e : set.tets) tet_sets[static_cast<std::size_t>(e)].push_back(name);
    if (set.dim == 2)
      for (const Triangle& t : set.triangles) {
        std::array<int, 3> key = t;
        std::sort(key.begin(), key.end());
        auto [it, added] = triangle_index.try_emplace(key, triangles.size());
        if (added) {
          triangles.push_back(t);
          triangle_sets.emplace_back();
        }
        triangle_sets[it->second].push_back(name);
      }
  }
  EntityPlan volumes, surfaces;
  for (std::size_t e = 0; e < tet_sets.size(); ++e) volumes.members[tet_sets[e]].push_back(e);
  for (std::size_t t = 0; t < triangles.size(); ++t) surfaces.members[triangle_sets[t]].push_back(t);

  GmshSession session;
  gmsh_call(output.string(), [&] {
    gmsh::model::add("roifem");
    std::map<std::string, std::vector<int>> groups[4];
    int entity = 0;
    for (const auto& [signature, elements] : volumes.members) {
      gmsh::model::addDiscreteEntity(3, ++entity);
      if (entity == 1) {  // every node on the first volume, in the mesh's order (read_mesh keeps file order)
        std::vector<std::size_t> tags(static_cast<std::size_t>(mesh.num_nodes()));
        std::iota(tags.begin(), tags.end(), std::size_t{1});
        std::vector<double> coords(3 * tags.size());
        for (Index i = 0; i < mesh.num_nodes(); ++i)
          for (int c = 0; c < 3; ++c) coords[static_cast<std::size_t>(3 * i + c)] = mesh.nodes(c, i) / length_unit;
        gmsh::model::mesh::addNodes(3, entity, tags, coords);
      }
      std::vector<std::size_t> tags, nodes;
      for (std::size_t e : elements) {
        tags.push_back(e + 1);
        for (int n : mesh.tets[e]) nodes.push_back(tag_of(n));
      }
      gmsh::model::mesh::addElementsByType(entity, msh_tet4, tags, nodes);
      for (const std::string& name : signature) groups[3][name].push_back(entity);
    }
    std::size_t next_tag = mesh.tets.size() + 1;
    entity = 0;
    for (const auto& [signature, elements] : surfaces.members) {
      gmsh::model::addDiscreteEntity(2, ++entity);
      std::vector<std::size_t> tags, nodes;
      for (std::size_t t : elements) {
        tags.push_back(next_tag++);
        for (int n : triangles[t]) nodes.push_back(tag_of(n));
      }
      gmsh::model::mesh::addElementsByType(entity, msh_triangle, tags, nodes);
      for (const std::string& name : signature) groups[2][name].push_back(entity);
    }
    for (int dim : {2, 3})
      for (const auto& [name, entities] : groups[dim])
        gmsh::model::setPhysicalName(dim, gmsh::model::addPhysicalGroup(dim, entities), name);
    AtomicFile file(output);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 0);
    gmsh::option::setNumber("Mesh.SaveAll", 1);  // keep tetrahedra that no named set lists
    gmsh::write(file.temporary_path().string());
    file.commit();
  });
}

}  // namespace roifem::mesh
