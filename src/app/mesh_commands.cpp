// roifem mesh / roifem info
#include <cstdio>
#include <iostream>

#include "app/commands.hpp"
#include "common/timer.hpp"
#include "common/types.hpp"
#include "mesh/brain_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"

namespace roifem::app {

void add_mesh_command(CLI::App& app, Action& action) {
  struct Options {
    Index nodes = 800;
    std::string out;
    double tolerance = 3;
    double slit_refinement = 1;
  };
  auto opts = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("mesh",
                                 "Generate a simplified brain mesh (ellipsoid 14 x 17 x 10 cm with a "
                                 "surgical opening) with Gmsh, in millimetres");
  cmd->add_option("--nodes", opts->nodes, "Number of nodes wanted (e.g. 800, 5000, 20000, 100000, 300000)")
      ->capture_default_str();
  cmd->add_option("--out", opts->out, "Output mesh file (.msh, Gmsh 4.1 ASCII)")->required();
  cmd->add_option("--tolerance", opts->tolerance, "Allowed deviation from --nodes, in percent")->capture_default_str();
  cmd->add_option("--slit-refinement", opts->slit_refinement,
                  "Element size at the opening's faces relative to the rest, graded back over 30 mm (1: uniform)")
      ->capture_default_str();
  cmd->callback([&action, opts] {
    action = [opts] {
      Stopwatch clock;
      mesh::BrainShape shape;
      shape.slit_refinement = opts->slit_refinement;
      const auto result = mesh::generate_brain_mesh(opts->nodes, opts->out, shape, opts->tolerance / 100.0);
      std::printf("wrote %s: %lld nodes, %lld tetrahedra (element size %.2f mm, %d meshings, %.1f s)\n", opts->out.c_str(),
                  static_cast<long long>(result.mesh.num_nodes()), static_cast<long long>(result.mesh.num_tets()),
                  result.element_size_mm, result.attempts, clock.seconds());
    };
  });
}

void add_info_command(CLI::App& app, Action& action) {
  auto file = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("info", "Print a mesh's size, volume, element quality, bounding box and named sets");
  cmd->add_option("MESH", *file, "Mesh file (any tetrahedral mesh Gmsh reads; lengths in mm)")->required();
  cmd->callback([&action, file] {
    action = [file] {
      const mesh::TetMesh m = mesh::read_mesh(*file);
      mesh::check_mesh(m);
      const auto s = mesh::mesh_statistics(m);
      const double to_mm = 1.0 / mm;
      std::printf("mesh          %s\n", file->c_str());
      std::printf("nodes         %lld\n", static_cast<long long>(s.nodes));
      std::printf("tetrahedra    %lld\n", static_cast<long long>(s.tets));
      std::printf("volume        %.6g mm^3 (%.4g cm^3)\n", s.volume * 1e9, s.volume * 1e6);
      std::printf("quality       min %.3f, median %.3f  (6 sqrt(2) V / l_rms^3; 1 = regular)\n", s.quality_min, s.quality_median);
      std::printf("bounding box  [%.2f, %.2f] x [%.2f, %.2f] x [%.2f, %.2f] mm\n", s.box_min.x() * to_mm, s.box_max.x() * to_mm,
                  s.box_min.y() * to_mm, s.box_max.y() * to_mm, s.box_min.z() * to_mm, s.box_max.z() * to_mm);
      std::printf("named sets    %zu\n", m.sets.size());
      for (const auto& [name, set] : m.sets)
        std::printf("  %-16s %dD  %6zu nodes  %6zu tetrahedra  %6zu triangles\n", name.c_str(), set.dim, set.nodes.size(),
                    set.tets.size(), set.triangles.size());
    };
  });
}

}  // namespace roifem::app
