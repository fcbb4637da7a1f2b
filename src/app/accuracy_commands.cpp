// SPDX-License-Identifier: GPL-3.0-or-later
// roifem convergence (the scenario's brain at several mesh sizes, experiments/convergence_study.hpp) and
// roifem model-error (linear against geometrically nonlinear, experiments/model_error.hpp).
#include <iostream>

#include "app/commands.hpp"
#include "common/errors.hpp"
#include "experiments/convergence_study.hpp"
#include "experiments/model_error.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"
#include "scenario/scenario.hpp"

namespace roifem::app {

void add_convergence_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<experiments::ConvergenceOptions>();
  auto element = std::make_shared<std::string>();
  auto material = std::make_shared<std::string>();
  auto probe_mm = std::make_shared<std::vector<double>>();
  auto* cmd = app.add_subcommand(
      "convergence",
      "How far the mesh is from converged: regenerates the scenario's brain at each --nodes size (same shape and named "
      "sets), applies the same loads, and reports the static opening, the displacement at the probe, the lowest "
      "eigenfrequencies and the probe over the dynamic run, with observed orders, Richardson-extrapolated values and each "
      "mesh's error. Writes convergence.csv, probe_history.csv, convergence.png and the meshes");
  cmd->add_option("SCENARIO", o->scenario, "Scenario file (.toml) on the generated brain (roifem mesh)")->required();
  cmd->add_option("--out", o->out, "Output directory (meshes/brain-N.msh there are reused)")->required();
  cmd->add_option("--nodes", o->nodes, "Node counts, increasing (at least two; three give an observed order)")
      ->capture_default_str();
  cmd->add_option("--element", *element, "Override the scenario's element: tet4, nodal-pressure or tet10");
  cmd->add_option("--material", *material, "Override the scenario's material with a preset: paper or brain");
  cmd->add_option("--probe-mm", *probe_mm, "Probe point X Y Z in mm (default: the ROI's target)")->expected(3);
  cmd->add_option("--slit-refinement", o->slit_refinement,
                  "Element size at the opening's faces relative to the rest, graded back over 30 mm (1: uniform meshes)")
      ->capture_default_str();
  cmd->add_option("--adapt", o->adapt_passes,
                  "Adapt each mesh this many times to the scenario's static solution: its recovered-strain error estimate "
                  "sets the sizes of the next mesh at the same node count (0: uniform or --slit-refinement meshes)")
      ->capture_default_str();
  cmd->add_flag("--c3d10", o->c3d10,
                "Also solve each mesh's static problem with quadratic tetrahedra (CalculiX C3D10 on the same nodes and "
                "edges) and report its opening");
  cmd->add_option("--modes", o->modes, "Eigenfrequencies compared")->capture_default_str();
  cmd->add_flag("!--no-dynamic", o->dynamic, "Skip the dynamic run on each mesh");
  cmd->add_flag("!--no-plots", o->plots, "Skip the PNG plot");
  cmd->callback([&action, o, element, material, probe_mm] {
    action = [o, element, material, probe_mm] {
      if (!element->empty()) o->element = fem::parse_element(*element);
      if (!material->empty()) o->material = *material;
      if (probe_mm->size() == 3) o->probe = Vec3((*probe_mm)[0], (*probe_mm)[1], (*probe_mm)[2]) * mm;
      experiments::run_convergence_study(*o, std::cout);
    };
  });
}

void add_model_error_command(CLI::App& app, Action& action) {
  struct Options {
    std::string scenario, out;
    std::vector<double> fractions{0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.5, 2.0, 3.0};
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "model-error",
      "How far small-strain theory holds: the scenario's static problem (its forces at full value) solved linearly by roifem "
      "and geometrically nonlinearly by CalculiX (ccx, NLGEOM, the same mesh and linear tetrahedra) at growing fractions of "
      "the load; prints the table and the opening up to which the linear answer stays within 10%");
  cmd->add_option("SCENARIO", o->scenario, "Scenario file (.toml) with set forces (tet4)")->required();
  cmd->add_option("--out", o->out, "Work directory (CalculiX's decks, logs and results stay there)")->required();
  cmd->add_option("--fractions", o->fractions, "Load fractions, ascending (1 = the scenario's load)")->capture_default_str();
  cmd->callback([&action, o] {
    action = [o] {
      const auto s = scenario::read_scenario(o->scenario);
      scenario::refuse_run_only_tables(s, "roifem model-error");
      if (!s.material_regions.empty())
        throw InputError(o->scenario + ": [[material_region]]: the CalculiX deck writes one material; give one [material]");
      const mesh::TetMesh mesh = mesh::read_mesh(s.mesh);
      mesh::check_mesh(mesh);
      const auto study =
          experiments::measure_model_error(mesh, s.material, s.fixed_sets, s.loads, o->fractions, o->out, std::cout);
      experiments::print_model_error(study, std::cout);
    };
  });
}

}  // namespace roifem::app
