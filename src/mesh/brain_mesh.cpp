// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/brain_mesh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/node_count_search.hpp"

namespace roifem::mesh {

namespace {

void validate(const BrainShape& s, Index target_nodes) {
  if (target_nodes < 100) throw InputError("--nodes " + std::to_string(target_nodes) + ": at least 100 nodes are needed");
  if (target_nodes > 5'000'000) throw InputError("--nodes " + std::to_string(target_nodes) + ": at most 5e6 nodes");
  if (s.semi_axis_x <= 0 || s.semi_axis_y <= 0 || s.semi_axis_z <= 0) throw InputError("brain semi-axes must be positive");
  if (s.slit_width <= 0 || s.slit_width >= s.semi_axis_x) throw InputError("slit width must lie in (0, semi_axis_x)");
  if (s.slit_depth <= 0 || s.slit_depth >= s.semi_axis_z) throw InputError("slit depth must lie in (0, semi_axis_z)");
  if (s.slit_length <= 0 || s.slit_length >= s.semi_axis_y) throw InputError("slit length must lie in (0, semi_axis_y)");
  if (!(s.slit_refinement > 0 && s.slit_refinement <= 1))
    throw InputError("--slit-refinement " + std::to_string(s.slit_refinement) + ": must lie in (0, 1] (1: a uniform mesh)");
  if (!(s.slit_grading_mm > 0)) throw InputError("slit grading distance must be positive");
}

/// Names the slit's planar faces, found by their centres of mass; returns them (left, right, floor).
std::vector<int> name_slit_faces(const BrainShape& s) {
  namespace occ = gmsh::model::occ;
  const double eps = 1e-6 * s.semi_axis_z, hw = s.slit_width / 2, hl = s.slit_length / 2;
  const double z_floor = s.semi_axis_z - s.slit_depth;
  std::vector<int> left, right, floor;
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  for (const auto& [dim, tag] : surfaces) {
    double x, y, z;
    occ::getCenterOfMass(dim, tag, x, y, z);
    if (std::abs(y) > hl + eps || z < z_floor - eps) continue;
    if (std::abs(x + hw) < eps)
      left.push_back(tag);
    else if (std::abs(x - hw) < eps)
      right.push_back(tag);
    else if (std::abs(z - z_floor) < eps && std::abs(x) < hw)
      floor.push_back(tag);
  }
  auto name_surfaces = [](const std::vector<int>& tags, const char* name) {
    if (tags.size() != 1) throw Error(std::string("internal: expected one surface for ") + name);
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, tags), name);
  };
  name_surfaces(left, "opening_left");
  name_surfaces(right, "opening_right");
  name_surfaces(floor, "opening_floor");
  return {left[0], right[0], floor[0]};
}

/// Builds the geometry in the current Gmsh model and names the physical groups; returns the slit's
/// faces (left, right, floor), none without the opening.
std::vector<int> build_geometry(const BrainShape& s) {
  namespace occ = gmsh::model::occ;
  gmsh::model::add("brain");
  const int ellipsoid = occ::addSphere(0, 0, 0, 1);
  occ::dilate({{3, ellipsoid}}, 0, 0, 0, s.semi_axis_x, s.semi_axis_y, s.semi_axis_z);
  const double top = s.semi_axis_z;
  gmsh::vectorpair cut{{3, ellipsoid}}, fragments;
  std::vector<gmsh::vectorpair> map;
  if (s.opening) {
    const int slit =
        occ::addBox(-s.slit_width / 2, -s.slit_length / 2, top - s.slit_depth, s.slit_width, s.slit_length, 2 * s.slit_depth);
    occ::cut({{3, ellipsoid}}, {{3, slit}}, cut, map);
  }
  // Split off the base so that its nodes can be named: a half-space below z_cut.
  const double z_cut = -s.semi_axis_z + 2 * s.semi_axis_z * s.base_fraction;
  const double big = 4 * std::max({s.semi_axis_x, s.semi_axis_y, s.semi_axis_z});
  const int below = occ::addBox(-big, -big, -big, 2 * big, 2 * big, big + z_cut);
  occ::fragment(cut, {{3, below}}, fragments, map);
  occ::synchronize();

  // Classify by centre of mass and volume (OCC bounding boxes of the B-spline ellipsoid are loose):
  // the half-space box minus the ellipsoid is the largest piece and goes; the piece whose centre
  // lies below z_cut is the base.
  const double ellipsoid_volume = 4.0 / 3.0 * std::numbers::pi * s.semi_axis_x * s.semi_axis_y * s.semi_axis_z;
  std::vector<int> brain, base;
  for (const auto& [dim, tag] : fragments) {
    if (dim != 3) continue;
    double volume = 0, x, y, z;
    occ::getMass(3, tag, volume);
    occ::getCenterOfMass(3, tag, x, y, z);
    if (volume > 1.5 * ellipsoid_volume) {
      occ::remove({{3, tag}}, true);
      continue;
    }
    brain.push_back(tag);
    if (z < z_cut) base.push_back(tag);
  }
  occ::synchronize();
  if (base.size() != 1 || brain.size() != 2) throw Error("internal: brain geometry has an unexpected topology");
  gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, brain), "brain");
  gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, base), "base");

  return s.opening ? name_slit_faces(s) : std::vector<int>{};
}

/// A size field smaller by slit_refinement at the slit's faces, growing linearly back to the full
/// size over slit_grading_mm; returns the threshold field, whose sizes follow h (set_sizes).
int add_slit_field(const BrainShape& s, const std::vector<int>& slit_faces) {
  namespace field = gmsh::model::mesh::field;
  if (!s.opening) {  // the box the slit would take, graded over slit_grading_mm (Gmsh's Box field)
    const int box = field::add("Box");
    field::setNumber(box, "XMin", -s.slit_width / 2);
    field::setNumber(box, "XMax", s.slit_width / 2);
    field::setNumber(box, "YMin", -s.slit_length / 2);
    field::setNumber(box, "YMax", s.slit_length / 2);
    field::setNumber(box, "ZMin", s.semi_axis_z - s.slit_depth);
    field::setNumber(box, "ZMax", s.semi_axis_z);
    field::setNumber(box, "Thickness", s.slit_grading_mm);
    field::setAsBackgroundMesh(box);
    return box;
  }
  const int distance = field::add("Distance");
  field::setNumbers(distance, "SurfacesList", std::vector<double>(slit_faces.begin(), slit_faces.end()));
  field::setNumber(distance, "NumPointsPerCurve", 60);
  const int threshold = field::add("Threshold");
  field::setNumber(threshold, "InField", distance);
  field::setNumber(threshold, "DistMin", s.slit_width / 2);
  field::setNumber(threshold, "DistMax", s.slit_width / 2 + s.slit_grading_mm);
  field::setAsBackgroundMesh(threshold);
  return threshold;
}

/// Meshes at size h: uniform, graded towards the slit (slit_field), or h * sizes.at(x) when sizes are
/// given (the callback reads h through `current_h`).
Index mesh_with_size(double h, int slit_field, const BrainShape& shape, const RelativeSizes& sizes, double& current_h) {
  gmsh::model::mesh::clear();
  if (slit_field > 0) {  // a Threshold field at the slit's faces, or a Box field without the opening
    gmsh::model::mesh::field::setNumber(slit_field, shape.opening ? "SizeMin" : "VIn", shape.slit_refinement * h);
    gmsh::model::mesh::field::setNumber(slit_field, shape.opening ? "SizeMax" : "VOut", h);
  }
  current_h = h;
  gmsh::option::setNumber("Mesh.MeshSizeMax", sizes.at ? sizes.largest * h : h);
  gmsh::option::setNumber("Mesh.MeshSizeMin", sizes.at ? 0.5 * sizes.smallest * h : 0.05 * h);
  gmsh::model::mesh::generate(3);
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric);
  return static_cast<Index>(tags.size());
}

}  // namespace

BrainMesh generate_brain_mesh(Index target_nodes, const std::filesystem::path& output, const BrainShape& shape, double tolerance,
                              const RelativeSizes& sizes) {
  validate(shape, target_nodes);
  if (sizes.at && shape.slit_refinement < 1)
    throw InputError("brain mesh: give either a slit refinement or adapted sizes, not both");
  if (sizes.at && !(sizes.smallest > 0 && sizes.smallest <= sizes.largest))
    throw InputError("brain mesh: adapted sizes need 0 < smallest <= largest");
  double current_h = 0;  // outlives the session, whose size callback reads it
  GmshSession session;
  BrainMesh result;
  gmsh_call("brain mesh generation", [&] {
    const std::vector<int> slit_faces = build_geometry(shape);
    const int slit_field = shape.slit_refinement < 1 ? add_slit_field(shape, slit_faces) : 0;
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    if (sizes.at) {
      // The sizes alone decide, everywhere: not the geometry's points, not the surface mesh's
      // sizes carried inwards. Gmsh gives millimetres; the sizes take metres.
      gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
      gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
      gmsh::model::mesh::setSizeCallback(
          [&sizes, &current_h](int, int, double x, double y, double z) { return current_h * sizes.at(Vec3(x, y, z) * mm); });
    } else {
      gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
    }
    // Gmsh's default Delaunay mesher on one thread: the same request gives the same mesh, bit
    // for bit (HXT, algorithm 10, is faster but its node count varies from run to run).
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);
    gmsh::option::setNumber("General.NumThreads", 1);

    // Initial size from N(h) ~ a/h^3 + b/h^2 + c/h (interior, surface and edge nodes), fitted on
    // this geometry's meshes from 800 nodes (h = 15.6 mm) to 300k (h = 1.48 mm), within 4%, and
    // scaled with its volume, surface and size; then a secant on log(nodes) against log(h), kept inside the bracket
    // [too many nodes, too few] and replaced by bisection when it would leave it. N(h) is a
    // staircase; on coarse meshes its steps can jump over the target (718 -> 889 nodes for a
    // 0.001 mm change), so when the bracket collapses the search starts again with another
    // surface mesher, whose staircase lies elsewhere.
    const double volume = 4.0 / 3.0 * std::numbers::pi * shape.semi_axis_x * shape.semi_axis_y * shape.semi_axis_z;
    const double reference_volume = 4.0 / 3.0 * std::numbers::pi * 70.0 * 85.0 * 50.0;
    const double scale = std::cbrt(volume / reference_volume);
    const double a = 7.873e5 * std::pow(scale, 3), b = 1.095e5 * std::pow(scale, 2), c = 2.114e3 * scale;
    const double target = static_cast<double>(target_nodes);
    double x = std::cbrt(target / a);  // x = 1/h: Newton on a x^3 + b x^2 + c x = target
    for (int k = 0; k < 50; ++k) x -= (a * x * x * x + b * x * x + c * x - target) / (3 * a * x * x + 2 * b * x + c);
    double h = 1.0 / x;
    const int surface_algorithms[] = {6, 5, 1};  // Frontal-Delaunay (Gmsh's default), Delaunay, MeshAdapt
    for (int algorithm : surface_algorithms) {
      gmsh::option::setNumber("Mesh.Algorithm", algorithm);
      NodeCountSearch search(target, h, -2.5);
      for (int attempt = 0; attempt < 12; ++attempt) {
        const auto n = static_cast<double>(mesh_with_size(search.size(), slit_field, shape, sizes, current_h));
        ++result.attempts;
        if (search.record(n, tolerance)) {
          result.element_size_mm = search.size();
          break;
        }
        if (search.stuck()) break;  // a gap in N(h)
      }
      h = search.size();
      if (result.element_size_mm > 0) break;
    }
    if (result.element_size_mm == 0)
      throw InputError("brain mesh: could not reach " + std::to_string(target_nodes) + " nodes within " +
                       std::to_string(tolerance * 100) + "% in " + std::to_string(result.attempts) + " meshings");
    if (!output.empty()) {
      AtomicFile file(output);
      gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
      gmsh::option::setNumber("Mesh.Binary", 0);
      gmsh::write(file.temporary_path().string());
      file.commit();
    }
    result.mesh = extract_tet_mesh(output.empty() ? "<generated brain>" : output.string(), mm);
  });
  return result;
}

}  // namespace roifem::mesh
