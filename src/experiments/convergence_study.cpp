// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/convergence_study.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/timer.hpp"
#include "experiments/calculix_static.hpp"
#include "experiments/richardson.hpp"
#include "fem/loads.hpp"
#include "fem/material_map.hpp"
#include "fem/recovery_estimate.hpp"
#include "fem/static_solve.hpp"
#include "integrators/trapezoid.hpp"
#include "io/plots.hpp"
#include "mesh/adapted_size_field.hpp"
#include "mesh/brain_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh/point_locator.hpp"
#include "mesh/quadratic_mesh.hpp"
#include "model/fem_model.hpp"
#include "model/spectrum.hpp"
#include "scenario/scenario.hpp"

namespace roifem::experiments {

namespace {

/// Refuses a scenario whose mesh is not the brain `roifem mesh` generates: the study regenerates it.
void check_generated_brain(const scenario::Scenario& s) {
  const mesh::TetMesh m = mesh::read_mesh(s.mesh);
  const mesh::BrainShape shape;
  const Vec3 lo = m.nodes.rowwise().minCoeff() / mm, hi = m.nodes.rowwise().maxCoeff() / mm;
  const Vec3 expected(shape.semi_axis_x, shape.semi_axis_y, shape.semi_axis_z);
  for (int d = 0; d < 3; ++d)
    if (std::abs(hi[d] - expected[d]) > 0.05 * expected[d] || std::abs(lo[d] + expected[d]) > 0.05 * expected[d])
      throw InputError(
          format("%s: the convergence study regenerates the brain of `roifem mesh` (%g x %g x %g mm), but the "
                 "scenario's mesh %s spans [%.1f, %.1f] x [%.1f, %.1f] x [%.1f, %.1f] mm",
                 s.file.c_str(), 2 * expected.x(), 2 * expected.y(), 2 * expected.z(), s.mesh.c_str(), lo.x(), hi.x(), lo.y(),
                 hi.y(), lo.z(), hi.z()));
  for (const char* set : {"opening_left", "opening_right"})
    if (!m.sets.contains(set)) throw InputError(s.mesh.string() + ": no set '" + set + "': not the generated brain");
}

Vec3 default_probe(const scenario::Scenario& s) {
  if (!s.roi || s.roi->kind == roi::RoiSpec::Kind::all || s.roi->kind == roi::RoiSpec::Kind::set)
    throw InputError(s.file.string() + ": the scenario's [roi] gives no target point; give one with --probe-mm X Y Z");
  return s.roi->center;
}

mesh::TetMesh brain_of(Index nodes, double slit_refinement, const std::filesystem::path& dir, std::ostream& log) {
  const auto file = dir / ("brain-" + std::to_string(nodes) +
                           (slit_refinement < 1 ? format("-slit%g", slit_refinement) : std::string()) + ".msh");
  if (std::filesystem::exists(file)) {
    log << "  reusing " << file.string() << "\n" << std::flush;
    return mesh::read_mesh(file);
  }
  const Stopwatch clock;
  mesh::BrainShape shape;
  shape.slit_refinement = slit_refinement;
  auto generated = mesh::generate_brain_mesh(nodes, file, shape);
  log << format("  meshed %s: %lld nodes in %.1f s\n", file.c_str(), static_cast<long long>(generated.mesh.num_nodes()),
                clock.seconds())
      << std::flush;
  return std::move(generated.mesh);
}

/// The static displacement (3N, every node) under the loads at the run's end.
Vector static_displacement(const model::FemModel& full, double t_end, solvers::Cholesky& K) {
  fem::factorize_stiffness(K, full.system.K, *full.dofs);
  return full.displacement(K.solve(full.system.load.at(t_end)), t_end);
}

/// The brain at `nodes` nodes after `passes` adaptations: each solves the static problem on the
/// last mesh, estimates its error (fem/recovery_estimate.hpp) and meshes again at the same node
/// count with the sizes that spread it evenly (mesh/adapted_size_field.hpp). The meshes are named
/// after the scenario, element and material they were adapted to, and reused when present.
mesh::TetMesh adapted_brain_of(Index nodes, const scenario::Scenario& s, const fem::Material& material, fem::Element element,
                               const std::string& material_name, const ConvergenceOptions& o, std::ostream& log) {
  const auto dir = o.out / "meshes";
  mesh::TetMesh mesh = brain_of(nodes, o.slit_refinement, dir, log);
  const double t_end = s.dt * static_cast<double>(s.steps);
  for (int pass = 1; pass <= o.adapt_passes; ++pass) {
    const auto file = dir / format("brain-%lld%s-adapted%d-%s-%s-%s.msh", static_cast<long long>(nodes),
                                   o.slit_refinement < 1 ? format("-slit%g", o.slit_refinement).c_str() : "", pass,
                                   s.file.stem().c_str(), std::string(fem::element_name(element)).c_str(), material_name.c_str());
    if (std::filesystem::exists(file)) {
      log << "  reusing " << file.string() << "\n" << std::flush;
      mesh = mesh::read_mesh(file);
      continue;
    }
    const Stopwatch clock;
    mesh::check_mesh(mesh);
    const model::FemModel full = model::build_fem_model(mesh, material, s.fixed_sets, s.loads, s.tools, element);
    solvers::Cholesky K;
    const Vector u = static_displacement(full, t_end, K);
    const fem::RecoveryEstimate estimate = fem::recovery_estimate(mesh, fem::MaterialMap(material), element, u);
    const Index previous_nodes = mesh.num_nodes();
    const mesh::AdaptedSizeField sizes(mesh, estimate.element_error2);
    const mesh::RelativeSizes relative{.at = [&sizes](const Vec3& x) { return sizes.relative_size(x); },
                                       .smallest = sizes.smallest(),
                                       .largest = sizes.largest()};
    mesh = mesh::generate_brain_mesh(nodes, file, mesh::BrainShape{}, 0.03, relative).mesh;
    log << format(
               "  adaptation %d: estimated energy error %.1f%% on %lld nodes; sizes %.2f to %.2f of the mean; meshed "
               "%s: %lld nodes (%.1f s)\n",
               pass, 100 * estimate.relative(), static_cast<long long>(previous_nodes), sizes.smallest(), sizes.largest(),
               file.c_str(), static_cast<long long>(mesh.num_nodes()), clock.seconds())
        << std::flush;
  }
  return mesh;
}

/// The static opening with quadratic tetrahedra on `mesh`, solved by CalculiX (linear, C3D10) in
/// `work_dir`; the loads at t_end, spread consistently over the sets' 6-node facets.
double c3d10_opening(const mesh::TetMesh& mesh, const scenario::Scenario& s, const fem::Material& material, double t_end,
                     const std::filesystem::path& work_dir, Index& dofs, std::ostream& log) {
  const mesh::TetMesh q = mesh::with_midside_nodes(mesh);
  dofs = 3 * q.num_nodes();
  CalculixProblem problem{.mesh = &q, .material = material, .forces = Vector::Zero(dofs)};
  for (const auto& load : s.loads) problem.forces += fem::set_force(q, load.set, load.force * load.ramp.value(t_end));
  for (const auto& set : s.fixed_sets)
    problem.fixed_nodes.insert(problem.fixed_nodes.end(), q.set(set).nodes.begin(), q.set(set).nodes.end());
  std::sort(problem.fixed_nodes.begin(), problem.fixed_nodes.end());
  problem.fixed_nodes.erase(std::unique(problem.fixed_nodes.begin(), problem.fixed_nodes.end()), problem.fixed_nodes.end());
  const Vector u = solve_with_calculix(problem, {1.0}, false, work_dir, log).front().u;
  return fem::set_mean_displacement(q, "opening_right", u).x() - fem::set_mean_displacement(q, "opening_left", u).x();
}

MeshQuantities measure(const scenario::Scenario& s, const fem::Material& material, fem::Element element,
                       const std::string& material_name, const Vec3& probe, const ConvergenceOptions& o, Index nodes,
                       std::ostream& log) {
  const Stopwatch clock;
  // The estimate is for linear elements: tet10 takes the meshes adapted for nodal pressures.
  const fem::Element adapted_for = element == fem::Element::tet10 ? fem::Element::nodal_pressure : element;
  const mesh::TetMesh linear = adapted_brain_of(nodes, s, material, adapted_for, material_name, o, log);
  mesh::check_mesh(linear);
  const mesh::TetMesh mesh = fem::element_mesh(linear, element);
  const model::FemModel full = model::build_fem_model(mesh, material, s.fixed_sets, s.loads, s.tools, element);
  const auto& system = full.system;
  MeshQuantities q;
  q.nodes = linear.num_nodes();
  q.tets = mesh.num_tets();
  q.dofs = system.size();
  q.h_mm = std::cbrt(6 * std::numbers::sqrt2 * mesh::total_volume(mesh) / static_cast<double>(q.tets)) / mm;
  const mesh::PointLocator locator(mesh);
  const mesh::PointLocation at_probe = locator.locate(probe);
  q.probe_outside_mm = at_probe.outside_distance / mm;
  const double t_end = s.dt * static_cast<double>(s.steps);
  {
    solvers::Cholesky K;
    const Vector u = static_displacement(full, t_end, K);
    if (element != fem::Element::tet10)
      q.estimated_error = fem::recovery_estimate(mesh, fem::MaterialMap(material), element, u).relative();
    q.opening_mm = opening_widening(mesh, u) / mm;
    q.probe_mm = mesh::PointLocator::interpolate(at_probe, u).norm() / mm;
    const model::Modes modes = model::lowest_modes(system.M.diagonal(), K, o.modes);
    for (Index i = 0; i < modes.omega.size(); ++i) q.frequencies_hz.push_back(modes.omega[i] / (2 * std::numbers::pi));
  }
  if (o.c3d10) {
    const Stopwatch ccx;
    q.c3d10_opening_mm =
        c3d10_opening(linear, s, material, t_end, o.out / "calculix" / format("c3d10-%lld", static_cast<long long>(q.nodes)),
                      q.c3d10_dofs, log) /
        mm;
    log << format("  C3D10 (CalculiX): %lld dofs, opening %.4f mm (%.1f s)\n", static_cast<long long>(q.c3d10_dofs),
                  q.c3d10_opening_mm, ccx.seconds())
        << std::flush;
  }
  if (o.dynamic) {
    integrators::Trapezoid trapezoid(s.dt);
    model::State state = model::State::at_rest(system.size());
    trapezoid.reset(system, state);
    for (long k = 0; k < s.steps; ++k) {
      trapezoid.step(state);
      q.probe_history_mm.push_back(mesh::PointLocator::interpolate(at_probe, full.displacement(state.u, state.t)).norm() / mm);
    }
  }
  q.seconds = clock.seconds();
  log << format("  %lld nodes, %lld dofs, h %.2f mm: opening %.4f mm, probe %.4f mm%s, f1 %.4f Hz%s (%.1f s)\n",
                static_cast<long long>(q.nodes), static_cast<long long>(q.dofs), q.h_mm, q.opening_mm, q.probe_mm,
                q.probe_outside_mm > 0 ? format(" (read at the boundary, %.2f mm away)", q.probe_outside_mm).c_str() : "",
                q.frequencies_hz.front(),
                element == fem::Element::tet10 ? "" : format(", estimated energy error %.1f%%", 100 * q.estimated_error).c_str(),
                q.seconds)
      << std::flush;
  return q;
}

QuantityConvergence converge(std::string name, std::string unit, const std::vector<double>& h, std::vector<double> values) {
  QuantityConvergence c{.name = std::move(name), .unit = std::move(unit), .values = std::move(values)};
  const auto e = richardson(h, c.values, formal_order);
  if (e.observed) c.observed_order = e.order;
  c.order_used = e.order;
  c.asymptotic = e.observed && std::abs(e.order - formal_order) <= 0.5 * formal_order;
  c.extrapolated = e.value;
  for (double v : c.values) c.errors.push_back(std::abs(v - e.value));
  return c;
}

/// The probe's history extrapolated step by step with the order used for the static probe; per
/// mesh, the largest distance over the run from it (the table shows that order in brackets).
void converge_history(ConvergenceResults& r, const std::vector<double>& h, double order, bool asymptotic) {
  const std::size_t n = r.meshes.size(), steps = r.meshes.front().probe_history_mm.size();
  QuantityConvergence c{.name = "dynamic peak", .unit = "mm"};
  c.order_used = order;
  c.asymptotic = asymptotic;  // the static probe's
  for (std::size_t k = 0; k < steps; ++k)
    r.extrapolated_history_mm.push_back(
        extrapolate(h[n - 2], h[n - 1], r.meshes[n - 2].probe_history_mm[k], r.meshes[n - 1].probe_history_mm[k], order));
  for (const auto& m : r.meshes) {
    c.values.push_back(*std::max_element(m.probe_history_mm.begin(), m.probe_history_mm.end()));
    double worst = 0;
    for (std::size_t k = 0; k < steps; ++k)
      worst = std::max(worst, std::abs(m.probe_history_mm[k] - r.extrapolated_history_mm[k]));
    c.errors.push_back(worst);
  }
  c.extrapolated = *std::max_element(r.extrapolated_history_mm.begin(), r.extrapolated_history_mm.end());
  r.quantities.push_back(std::move(c));
}

}  // namespace

double opening_widening(const mesh::TetMesh& mesh, const Vector& u) {
  return fem::set_mean_displacement(mesh, "opening_right", u).x() - fem::set_mean_displacement(mesh, "opening_left", u).x();
}

ConvergenceResults run_convergence_study(const ConvergenceOptions& o, std::ostream& log) {
  if (o.nodes.size() < 2) throw InputError("--nodes: a convergence study needs at least two mesh sizes");
  if (!std::is_sorted(o.nodes.begin(), o.nodes.end()) || std::adjacent_find(o.nodes.begin(), o.nodes.end()) != o.nodes.end())
    throw InputError("--nodes: give the sizes in increasing order, each once");
  if (o.modes < 1) throw InputError("--modes: at least one eigenfrequency");
  if (o.adapt_passes < 0 || o.adapt_passes > 6) throw InputError("--adapt: give 0 to 6 adaptation passes");
  const scenario::Scenario s = scenario::read_scenario(o.scenario);
  scenario::refuse_run_only_tables(s, "roifem convergence");
  check_generated_brain(s);
  if (o.c3d10) {
    if (!s.tools.empty()) throw InputError(s.file.string() + ": --c3d10 takes set forces only, not tools");
    for (const auto& load : s.loads)
      if (load.gravity) throw InputError(s.file.string() + ": --c3d10 takes set forces only, not gravity");
  }
  if (!s.material_regions.empty())
    throw InputError(s.file.string() +
                     ": [[material_region]]: the convergence study regenerates the ellipsoid brain, which has no "
                     "material regions; give one [material]");
  ConvergenceResults r;
  const fem::Material material = o.material ? fem::material_preset(*o.material) : s.material;
  const fem::Element element = o.element.value_or(s.element);
  r.material = o.material.value_or(s.material_name);
  r.element = std::string(fem::element_name(element));
  r.probe = o.probe.value_or(default_probe(s));
  r.dt = s.dt;
  std::filesystem::create_directories(o.out / "meshes");
  log << format("convergence study: %s, element %s, material '%s', probe (%.1f, %.1f, %.1f) mm, %zu meshes\n", o.scenario.c_str(),
                r.element.c_str(), r.material.c_str(), r.probe.x() / mm, r.probe.y() / mm, r.probe.z() / mm, o.nodes.size());
  for (const Index n : o.nodes) r.meshes.push_back(measure(s, material, element, r.material, r.probe, o, n, log));

  std::vector<double> h;
  for (const auto& m : r.meshes) h.push_back(m.h_mm);
  auto values = [&](auto pick) {
    std::vector<double> v;
    for (const auto& m : r.meshes) v.push_back(pick(m));
    return v;
  };
  r.quantities.push_back(converge("opening", "mm", h, values([](const MeshQuantities& m) { return m.opening_mm; })));
  if (o.c3d10)
    r.quantities.push_back(
        converge("opening c3d10", "mm", h, values([](const MeshQuantities& m) { return m.c3d10_opening_mm; })));
  r.quantities.push_back(converge("probe", "mm", h, values([](const MeshQuantities& m) { return m.probe_mm; })));
  for (int i = 0; i < o.modes; ++i)
    r.quantities.push_back(converge("f" + std::to_string(i + 1), "Hz", h, values([i](const MeshQuantities& m) {
                                      return m.frequencies_hz[static_cast<std::size_t>(i)];
                                    })));
  if (o.dynamic) {
    const auto probe = std::find_if(r.quantities.begin(), r.quantities.end(), [](const auto& q) { return q.name == "probe"; });
    converge_history(r, h, std::clamp(probe->order_used, 0.3, 4.0), probe->asymptotic);
  }

  print_convergence_table(r, log);
  write_convergence_csv(r, o.out);
  if (o.plots && io::run_plot_script("plot_convergence.py", o.out, log))
    log << "plots: " << (o.out / "convergence.png").string() << '\n';
  log << "results: " << (o.out / "convergence.csv").string()
      << (o.dynamic ? ", " + (o.out / "probe_history.csv").string() : std::string()) << ", meshes in "
      << (o.out / "meshes").string() << '\n';
  return r;
}

}  // namespace roifem::experiments
