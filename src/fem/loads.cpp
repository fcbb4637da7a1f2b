// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/loads.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "fem/assembly.hpp"
#include "fem/tet10.hpp"

namespace roifem::fem {

mesh::Triangle facet_load_nodes(const mesh::TetMesh& mesh, const mesh::Triangle& t) {
  if (!mesh.is_quadratic()) return t;
  const mesh::Triangle mid{mesh.midside.at(t[0], t[1]), mesh.midside.at(t[1], t[2]), mesh.midside.at(t[2], t[0])};
  if (std::find(mid.begin(), mid.end(), -1) != mid.end())
    throw InputError(
        format("%s: the triangle with corners %d, %d, %d (0-based) is not a face of the tetrahedra: an edge "
               "of it is no tetrahedron's",
               mesh.source.c_str(), t[0], t[1], t[2]));
  return mid;
}

Vector set_force(const mesh::TetMesh& mesh, const std::string& set_name, const Vec3& total_force) {
  const auto& set = mesh.set(set_name);
  if (set.nodes.empty()) throw InputError(mesh.source + ": named set '" + set_name + "' has no nodes to load");
  if (!total_force.allFinite()) throw InputError("force on set '" + set_name + "' is NaN or infinite");
  Vector weight = Vector::Zero(mesh.num_nodes());
  if (!set.triangles.empty()) {
    for (const auto& tri : set.triangles) {
      const double area = 0.5 * (mesh.node(tri[1]) - mesh.node(tri[0])).cross(mesh.node(tri[2]) - mesh.node(tri[0])).norm();
      for (int a : facet_load_nodes(mesh, tri)) weight[a] += area / 3.0;
    }
  } else if (!set.tets.empty()) {
    for (int e : set.tets) {
      const double volume = std::abs(mesh::signed_volume(mesh, e));
      if (mesh.is_quadratic()) {
        for (int a : mesh.tets[static_cast<std::size_t>(e)]) weight[a] += tet10_corner_mass * volume;
        for (int a : mesh.midside.of_tet[static_cast<std::size_t>(e)]) weight[a] += tet10_midside_mass * volume;
        continue;
      }
      for (int a : mesh.tets[static_cast<std::size_t>(e)]) weight[a] += volume / 4.0;
    }
  } else {
    for (int a : set.nodes) weight[a] = 1.0;
  }
  weight /= weight.sum();
  Vector f = Vector::Zero(3 * mesh.num_nodes());
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (weight[n] != 0) f.segment<3>(3 * n) = weight[n] * total_force;
  return f;
}

Vec3 set_mean_displacement(const mesh::TetMesh& mesh, const std::string& set_name, const Vector& u) {
  double area = 0;
  Vec3 sum = Vec3::Zero();
  for (const auto& f : mesh.set(set_name).triangles) {
    const Vec3 a = mesh.node(f[0]), b = mesh.node(f[1]), c = mesh.node(f[2]);
    const double A = 0.5 * (b - a).cross(c - a).norm();
    area += A;
    const mesh::Triangle at = facet_load_nodes(mesh, f);
    sum += A / 3 * (u.segment<3>(3 * at[0]) + u.segment<3>(3 * at[1]) + u.segment<3>(3 * at[2]));
  }
  if (area <= 0) throw InputError(mesh.source + ": set '" + set_name + "' has no boundary triangles to average over");
  return sum / area;
}

Vector gravity_force(const mesh::TetMesh& mesh, double rho, const Vec3& g) {
  return gravity_force(mesh, MaterialMap(Material{0, 0, rho, 0}), g);
}

Vector gravity_force(const mesh::TetMesh& mesh, const MaterialMap& materials, const Vec3& g) {
  const Vector m = lumped_node_mass(mesh, materials);
  Vector f(3 * mesh.num_nodes());
  for (Index n = 0; n < mesh.num_nodes(); ++n) f.segment<3>(3 * n) = m[n] * g;
  return f;
}

}  // namespace roifem::fem
