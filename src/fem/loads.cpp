#include "fem/loads.hpp"

#include "common/errors.hpp"
#include "fem/assembly.hpp"

namespace roifem::fem {

Vector set_force(const mesh::TetMesh& mesh, const std::string& set_name, const Vec3& total_force) {
  const auto& set = mesh.set(set_name);
  if (set.nodes.empty()) throw InputError(mesh.source + ": named set '" + set_name + "' has no nodes to load");
  if (!total_force.allFinite()) throw InputError("force on set '" + set_name + "' is NaN or infinite");
  Vector weight = Vector::Zero(mesh.num_nodes());
  if (!set.triangles.empty()) {
    for (const auto& tri : set.triangles) {
      const double area = 0.5 * (mesh.node(tri[1]) - mesh.node(tri[0])).cross(mesh.node(tri[2]) - mesh.node(tri[0])).norm();
      for (int a : tri) weight[a] += area / 3.0;
    }
  } else if (!set.tets.empty()) {
    for (int e : set.tets)
      for (int a : mesh.tets[static_cast<std::size_t>(e)]) weight[a] += std::abs(mesh::signed_volume(mesh, e)) / 4.0;
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
    sum += A / 3 * (u.segment<3>(3 * f[0]) + u.segment<3>(3 * f[1]) + u.segment<3>(3 * f[2]));
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
