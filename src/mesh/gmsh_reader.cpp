// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/gmsh_reader.hpp"

#include <gmsh.h>

#include <algorithm>
#include <fstream>
#include <new>
#include <unordered_map>

#include "common/errors.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/msh2_diagnosis.hpp"
#include "mesh/msh_header_check.hpp"

namespace roifem::mesh {

namespace {

constexpr int gmsh_triangle = 2;
constexpr int gmsh_tet4 = 4;
constexpr int gmsh_tet10 = 11;

/// Gmsh node tag -> 0-based index among the nodes the tetrahedra use.
class NodeNumbering {
 public:
  NodeNumbering(const std::string& source, const std::vector<std::size_t>& tags) : source_(source) {
    index_.reserve(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i) index_.emplace(tags[i], static_cast<int>(i));
  }
  int operator()(std::size_t tag) const {
    auto it = index_.find(tag);
    if (it == index_.end())
      throw InputError(source_ + ": an element names node tag " + std::to_string(tag) + ", which is not defined");
    return it->second;
  }

 private:
  std::string source_;
  std::unordered_map<std::size_t, int> index_;
};

std::string group_name(int dim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(dim, tag, name);
  return name.empty() ? "physical_" + std::to_string(dim) + "d_" + std::to_string(tag) : name;
}

}  // namespace

TetMesh extract_tet_mesh(const std::string& source, double length_unit) {
  return gmsh_call(source, [&] {
    TetMesh mesh;
    mesh.source = source;

    std::vector<std::size_t> node_tags;
    std::vector<double> coords, parametric;
    gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, /*includeBoundary=*/true, false);
    const NodeNumbering numbering(source, node_tags);

    std::vector<std::size_t> tet_tags, tet_nodes;
    gmsh::model::mesh::getElementsByType(gmsh_tet4, tet_tags, tet_nodes);
    if (tet_tags.empty()) {
      std::vector<std::size_t> tags10, nodes10;
      gmsh::model::mesh::getElementsByType(gmsh_tet10, tags10, nodes10);
      if (!tags10.empty())
        throw InputError(source + ": has " + std::to_string(tags10.size()) +
                         " 10-node tetrahedra; roifem needs linear 4-node tetrahedra (Mesh.ElementOrder = 1), "
                         "and adds the midpoints itself for the scenario key element = \"tet10\"");
      throw InputError(source + ": the mesh has no tetrahedra (is it a surface mesh?)");
    }

    // Keep only nodes that tetrahedra use, in their original order.
    std::vector<int> new_index(node_tags.size(), -1);
    for (std::size_t tag : tet_nodes) new_index[static_cast<std::size_t>(numbering(tag))] = 0;
    int count = 0;
    for (int& i : new_index)
      if (i == 0) i = count++;
    mesh.nodes.resize(3, count);
    for (std::size_t i = 0; i < node_tags.size(); ++i)
      if (new_index[i] >= 0)
        for (int c = 0; c < 3; ++c) mesh.nodes(c, new_index[i]) = coords[3 * i + static_cast<std::size_t>(c)] * length_unit;
    auto index_of = [&](std::size_t tag) { return new_index[static_cast<std::size_t>(numbering(tag))]; };

    mesh.tets.resize(tet_tags.size());
    std::unordered_map<std::size_t, int> tet_index;
    tet_index.reserve(tet_tags.size());
    for (std::size_t e = 0; e < tet_tags.size(); ++e) {
      for (std::size_t a = 0; a < 4; ++a) mesh.tets[e][a] = index_of(tet_nodes[4 * e + a]);
      tet_index.emplace(tet_tags[e], static_cast<int>(e));
    }

    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    for (const auto& [dim, tag] : groups) {
      NamedSet& set = mesh.sets[group_name(dim, tag)];
      set.dim = dim;
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
      struct {
        std::size_t count = 0, triangle = 0, node = 0;  // the first one's Gmsh tags
      } dropped;
      for (int entity : entities) {
        std::vector<std::size_t> etags, enodes;
        if (dim == 3) {
          gmsh::model::mesh::getElementsByType(gmsh_tet4, etags, enodes, entity);
          for (std::size_t t : etags) set.tets.push_back(tet_index.at(t));
        } else if (dim == 2) {
          gmsh::model::mesh::getElementsByType(gmsh_triangle, etags, enodes, entity);
          for (std::size_t k = 0; k + 2 < enodes.size(); k += 3) {
            const Triangle t{index_of(enodes[k]), index_of(enodes[k + 1]), index_of(enodes[k + 2])};
            const auto orphan = std::find(t.begin(), t.end(), -1);
            if (orphan == t.end()) {
              set.triangles.push_back(t);
            } else if (dropped.count++ == 0) {
              dropped.triangle = etags[k / 3];
              dropped.node = enodes[k + static_cast<std::size_t>(orphan - t.begin())];
            }
          }
        }
      }
      // A face over no tissue (what deleting a cut's tetrahedra leaves) carries no load and holds
      // nothing: it is dropped, and said.
      if (dropped.count > 0)
        mesh.warnings.push_back(source + ": set '" + group_name(dim, tag) + "': dropped " + std::to_string(dropped.count) +
                                " triangle(s) over nodes that no tetrahedron uses (the first: triangle " +
                                std::to_string(dropped.triangle) + ", node " + std::to_string(dropped.node) +
                                ", Gmsh's tags); no tissue lies under them" +
                                (set.triangles.empty() ? "; the set is left empty" : ""));
      std::vector<std::size_t> group_nodes;
      std::vector<double> group_coords;
      // A surface set that lost every triangle holds nothing: it is not kept as a cloud of loose nodes.
      if (!(dropped.count > 0 && set.triangles.empty()))
        gmsh::model::mesh::getNodesForPhysicalGroup(dim, tag, group_nodes, group_coords);
      for (std::size_t t : group_nodes) {
        const int i = new_index[static_cast<std::size_t>(numbering(t))];
        if (i >= 0) set.nodes.push_back(i);  // a node no tetrahedron uses carries no stiffness
      }
      std::sort(set.nodes.begin(), set.nodes.end());
      set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
      std::sort(set.tets.begin(), set.tets.end());
    }
    return mesh;
  });
}

TetMesh read_mesh(const std::filesystem::path& file, double length_unit) {
  const std::string source = file.string();
  // Gmsh 4.8 only warns about a missing file; check first so the error is ours and clear.
  if (std::filesystem::is_directory(file)) throw InputError(source + ": is a directory, not a mesh file (.msh)");
  if (!std::filesystem::is_regular_file(file)) throw InputError(source + ": no such mesh file");
  if (!std::ifstream(file)) throw InputError(source + ": cannot open the mesh file for reading");
  if (std::filesystem::file_size(file) == 0) throw InputError(source + ": the mesh file is empty");
  check_msh_header_counts(file);
  GmshSession session;
  try {
    gmsh_call(source, [&] { gmsh::open(source); });
  } catch (const InputError&) {
    const std::string where = diagnose_msh2_ascii(file);  // Gmsh names no line for MSH 2
    if (where.empty()) throw;
    throw InputError(source + ":" + where);
  } catch (const std::bad_alloc&) {
    throw InputError(source + ": Gmsh ran out of memory reading it (a corrupt count in a binary header?)");
  }
  return extract_tet_mesh(source, length_unit);
}

}  // namespace roifem::mesh
