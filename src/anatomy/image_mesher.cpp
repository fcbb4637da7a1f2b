// SPDX-License-Identifier: GPL-3.0-or-later
#include "anatomy/image_mesher.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Image_3.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Random.h>
#include <CGAL/make_mesh_3.h>

#include <algorithm>
#include <cstring>
#include <unordered_map>

#include "common/errors.hpp"

namespace roifem::anatomy {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<Kernel>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;

/// A CGAL image over the grid's voxels, spaced by the voxel sizes, origin at voxel (0, 0, 0):
/// CGAL's point p is voxel index p / spacing.
CGAL::Image_3 to_cgal_image(const ImageVolume& image, const Eigen::Vector3d& spacing) {
  _image* raw = ::_createImage(static_cast<std::size_t>(image.dims[0]), static_cast<std::size_t>(image.dims[1]),
                               static_cast<std::size_t>(image.dims[2]), 1, spacing.x(), spacing.y(), spacing.z(), sizeof(float),
                               WK_FLOAT, SGN_SIGNED);
  if (raw == nullptr) throw Error("internal: CGAL could not allocate a " + std::to_string(image.size()) + "-voxel image");
  std::memcpy(raw->data, image.values.data(), image.size() * sizeof(float));  // both x fastest
  return CGAL::Image_3(raw);
}

/// The facet and cell size at a point: size_mm, or less near the refinement box. CGAL's points
/// are in the grid's frame; `to_world` maps them to the box's millimetres.
class SizeField {
 public:
  SizeField(const ImageMeshSizes& sizes, const Eigen::Matrix3d& linear, const Eigen::Vector3d& offset)
      : sizes_(sizes), linear_(linear), offset_(offset) {}
  template <class Point, class DomainIndex>
  Kernel::FT operator()(const Point& p, int /*dimension*/, const DomainIndex& /*index*/) const {
    if (!sizes_.refine_box_mm) return sizes_.size_mm;
    const Eigen::Vector3d x =
        linear_ * Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())) + offset_;
    const auto& [lo, hi] = *sizes_.refine_box_mm;
    const double distance = (lo - x).cwiseMax(x - hi).cwiseMax(0.0).norm();
    return std::min(sizes_.size_mm, sizes_.refine_size_mm + 0.5 * distance);
  }

 private:
  ImageMeshSizes sizes_;
  Eigen::Matrix3d linear_;
  Eigen::Vector3d offset_;
};

}  // namespace

RawTetMesh mesh_image_level_set(const ImageVolume& image, double iso, const ImageMeshSizes& sizes, unsigned seed) {
  namespace params = CGAL::parameters;
  const Eigen::Vector3d spacing = image.spacing_mm();
  const CGAL::Image_3 cgal_image = to_cgal_image(image, spacing);
  CGAL::Random random(seed);
  CGAL::get_default_random() = CGAL::Random(seed);  // Mesh_3 draws some points from CGAL's default generator
  const Domain domain = Domain::create_gray_image_mesh_domain(cgal_image, params::iso_value = static_cast<float>(iso),
                                                              params::value_outside = 0.0f, params::p_rng = &random);
  // CGAL 5.5's named parameters are Boost.Parameter keywords (name = value), not 6.x's chained calls.
  const Eigen::Matrix3d linear = image.index_to_mm.topLeftCorner<3, 3>() * spacing.cwiseInverse().asDiagonal();
  const Eigen::Vector3d offset = image.index_to_mm.topRightCorner<3, 1>();
  const SizeField size(sizes, linear, offset);
  const Criteria criteria(params::facet_angle = sizes.facet_angle_deg, params::facet_size = size,
                          params::facet_distance = sizes.distance_mm, params::cell_radius_edge_ratio = sizes.radius_edge,
                          params::cell_size = size);
  // Perturbation and exudation stop, by default, after as much time as the refinement took: wall
  // clock, so a loaded machine gave another mesh. Without a time limit they stop at a bound on the
  // smallest dihedral angle (10 degrees) or when they cannot improve it any more: the same input
  // gives the same mesh.
  const Complex complex = CGAL::make_mesh_3<Complex>(domain, criteria, params::manifold(),
                                                     params::perturb(params::time_limit = 0, params::sliver_bound = 10),
                                                     params::exude(params::time_limit = 0, params::sliver_bound = 10));

  RawTetMesh mesh;
  std::unordered_map<Triangulation::Vertex_handle, int> index;
  std::vector<Eigen::Vector3d> points;
  for (auto cell = complex.cells_in_complex_begin(); cell != complex.cells_in_complex_end(); ++cell) {
    std::array<int, 4> tet{};
    for (int a = 0; a < 4; ++a) {
      const auto vertex = cell->vertex(a);
      auto [it, added] = index.try_emplace(vertex, static_cast<int>(points.size()));
      if (added) {
        const auto& p = vertex->point().point();
        const Eigen::Vector3d local(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
        points.emplace_back(linear * local + offset);
      }
      tet[static_cast<std::size_t>(a)] = it->second;
    }
    mesh.tets.push_back(tet);
  }
  mesh.points_mm.resize(3, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) mesh.points_mm.col(static_cast<Eigen::Index>(i)) = points[i];
  for (auto& t : mesh.tets) {  // an affine that mirrors (det < 0) turns every cell inside out
    const Eigen::Vector3d p0 = mesh.points_mm.col(t[0]);
    Eigen::Matrix3d edges;
    for (int a = 1; a < 4; ++a) edges.col(a - 1) = mesh.points_mm.col(t[static_cast<std::size_t>(a)]) - p0;
    if (edges.determinant() < 0) std::swap(t[2], t[3]);
  }
  return mesh;
}

}  // namespace roifem::anatomy
