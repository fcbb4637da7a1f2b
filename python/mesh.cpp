// SPDX-License-Identifier: GPL-3.0-or-later
// roifem.Mesh: a tetrahedral mesh read from a Gmsh file, generated, or a simulation's own.
#include <filesystem>

#include "bindings.hpp"
#include "mesh/brain_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh_handle.hpp"

namespace roifem::python {

namespace {

py::dict set_dict(const std::shared_ptr<const mesh::TetMesh>& mesh, const mesh::NamedSet& set) {
  py::dict d;
  d["dim"] = set.dim;
  d["nodes"] = owned_view(set.nodes.data(), static_cast<py::ssize_t>(set.nodes.size()), 0, mesh);
  d["tets"] = owned_view(set.tets.data(), static_cast<py::ssize_t>(set.tets.size()), 0, mesh);
  const int* triangles = set.triangles.empty() ? nullptr : set.triangles.front().data();
  d["triangles"] = owned_view(triangles, static_cast<py::ssize_t>(set.triangles.size()), 3, mesh);
  return d;
}

}  // namespace

void bind_mesh(py::module_& m) {
  py::class_<Mesh>(m, "Mesh",
                   "A linear tetrahedral mesh: nodes (N x 3, metres), tets (E x 4, 0-based, positively oriented) "
                   "and named sets (Gmsh physical groups). Arrays are read-only views of the mesh's own storage.")
      .def_property_readonly(
          "nodes", [](const Mesh& self) { return owned_view(self.mesh->nodes.data(), self.mesh->num_nodes(), 3, self.mesh); },
          "N x 3 node coordinates (m), a read-only view")
      .def_property_readonly(
          "nodes_mm",
          [](const Mesh& self) {
            const Eigen::Matrix3Xd in_mm = self.mesh->nodes / mm;  // 3 x N: row-major N x 3
            return copied_array(in_mm.data(), in_mm.size(), 3);
          },
          "N x 3 node coordinates (mm, as in the .msh file and results.h5), a copy")
      .def_property_readonly(
          "tets",
          [](const Mesh& self) {
            const int* data = self.mesh->tets.empty() ? nullptr : self.mesh->tets.front().data();
            return owned_view(data, self.mesh->num_tets(), 4, self.mesh);
          },
          "E x 4 node indices (0-based, int32), a read-only view")
      .def_property_readonly(
          "num_nodes", [](const Mesh& self) { return self.mesh->num_nodes(); }, "N, the number of nodes")
      .def_property_readonly(
          "num_tets", [](const Mesh& self) { return self.mesh->num_tets(); }, "E, the number of tetrahedra")
      .def_property_readonly(
          "source", [](const Mesh& self) { return self.mesh->source; }, "the file it came from")
      .def_property_readonly(
          "set_names",
          [](const Mesh& self) {
            std::vector<std::string> names;
            for (const auto& [name, set] : self.mesh->sets) names.push_back(name);
            return names;
          },
          "the named sets, sorted")
      .def(
          "set", [](const Mesh& self, const std::string& name) { return set_dict(self.mesh, self.mesh->set(name)); },
          py::arg("name"),
          "A named set as a dict: dim (0-3), nodes (sorted), tets (3D sets), triangles (2D sets, T x 3). "
          "InputError, listing the sets there are, for a name the mesh lacks.")
      .def(
          "statistics",
          [](const Mesh& self) {
            const mesh::MeshStatistics s = mesh::mesh_statistics(*self.mesh);
            py::dict d;
            d["nodes"] = s.nodes;
            d["tets"] = s.tets;
            d["volume_m3"] = s.volume;
            d["quality_min"] = s.quality_min;
            d["quality_median"] = s.quality_median;
            d["box_min_m"] = std::vector<double>(s.box_min.data(), s.box_min.data() + 3);
            d["box_max_m"] = std::vector<double>(s.box_max.data(), s.box_max.data() + 3);
            return d;
          },
          "volume (m^3), shape quality (1: regular) and bounding box, as `roifem info` prints them")
      .def("__repr__", [](const Mesh& self) {
        return "<roifem.Mesh " + self.mesh->source + ": " + std::to_string(self.mesh->num_nodes()) + " nodes, " +
               std::to_string(self.mesh->num_tets()) + " tetrahedra>";
      });

  m.def(
      "read_mesh",
      [](const std::filesystem::path& file) {
        auto mesh = std::make_shared<mesh::TetMesh>(mesh::read_mesh(file));
        mesh::check_mesh(*mesh);
        return Mesh{std::move(mesh)};
      },
      py::arg("file"),
      "Reads a Gmsh mesh (MSH 2.2 or 4.1, coordinates in mm) and checks it: InputError naming the file and the "
      "element or node for a malformed or inverted mesh.");
  m.def(
      "generate_brain_mesh",
      [](long nodes, const std::optional<std::filesystem::path>& out, double tolerance) {
        auto made = mesh::generate_brain_mesh(nodes, out.value_or(std::filesystem::path{}), {}, tolerance);
        return Mesh{std::make_shared<mesh::TetMesh>(std::move(made.mesh))};
      },
      py::arg("nodes"), py::arg("out") = py::none(), py::arg("tolerance") = 0.03,
      "The simplified brain of `roifem mesh` (an ellipsoid with a surgical opening; sets brain, base, "
      "opening_left, opening_right, opening_floor) with `nodes` nodes within `tolerance`, written to `out` "
      "(MSH 4.1) when given.");
}

}  // namespace roifem::python
