// SPDX-License-Identifier: GPL-3.0-or-later
#include "roi/roi.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <sstream>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::roi {

std::string RoiSpec::describe() const {
  std::ostringstream s;
  switch (kind) {
    case Kind::all:
      s << "all nodes";
      break;
    case Kind::ball:
      s << "ball of radius " << radius / mm << " mm around (" << center.x() / mm << ", " << center.y() / mm << ", "
        << center.z() / mm << ") mm";
      break;
    case Kind::nearest:
      s << count << " nodes nearest (" << center.x() / mm << ", " << center.y() / mm << ", " << center.z() / mm << ") mm";
      break;
    case Kind::set:
      s << "named set '" << set << "'";
      break;
  }
  return s.str();
}

namespace {

/// "(x, y, z) to (x, y, z) mm", to 0.1 mm.
std::string box_text(const Vec3& low, const Vec3& high) {
  char text[160];
  std::snprintf(text, sizeof text, "(%.1f, %.1f, %.1f) to (%.1f, %.1f, %.1f) mm", low.x() / mm, low.y() / mm, low.z() / mm,
                high.x() / mm, high.y() / mm, high.z() / mm);
  return text;
}

}  // namespace

std::vector<int> free_nodes(const mesh::TetMesh& mesh, const fem::DofMap& dofs) {
  std::vector<int> nodes;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (dofs.free_dof(n, 0) >= 0 || dofs.free_dof(n, 1) >= 0 || dofs.free_dof(n, 2) >= 0) nodes.push_back(n);
  return nodes;
}

std::vector<int> select_roi_nodes(const mesh::TetMesh& mesh, const fem::DofMap& dofs, const RoiSpec& spec) {
  const std::vector<int> free = free_nodes(mesh, dofs);
  std::vector<int> roi;
  switch (spec.kind) {
    case RoiSpec::Kind::all:
      roi = free;
      break;
    case RoiSpec::Kind::ball:
      if (!(spec.radius > 0)) throw InputError("ROI ball radius " + number_text(spec.radius / mm) + " mm must be positive");
      for (int n : free)
        if ((mesh.node(n) - spec.center).norm() <= spec.radius) roi.push_back(n);
      break;
    case RoiSpec::Kind::nearest: {
      if (spec.count <= 0) throw InputError("ROI node count " + std::to_string(spec.count) + " must be positive");
      if (spec.count > static_cast<Index>(free.size()))
        throw ModelError("ROI of " + std::to_string(spec.count) + " nodes asked, but the mesh has only " +
                         std::to_string(free.size()) + " free nodes");
      // A target outside the mesh would silently pick boundary nodes (a length in metres read as
      // millimetres does that): refuse a target outside the mesh's bounding box.
      const Vec3 low = mesh.nodes.rowwise().minCoeff(), high = mesh.nodes.rowwise().maxCoeff();
      if ((spec.center.array() < low.array()).any() || (spec.center.array() > high.array()).any())
        throw ModelError("ROI target (" + spec.describe() + ") lies outside the mesh " + mesh.source + ", whose box is (" +
                         number_text(low.x() / mm) + ", " + number_text(low.y() / mm) + ", " + number_text(low.z() / mm) +
                         ") to (" + number_text(high.x() / mm) + ", " + number_text(high.y() / mm) + ", " +
                         number_text(high.z() / mm) + ") mm");
      roi = free;
      auto distance = [&](int n) { return (mesh.node(n) - spec.center).squaredNorm(); };
      std::nth_element(roi.begin(), roi.begin() + spec.count - 1, roi.end(),
                       [&](int a, int b) { return distance(a) < distance(b) || (distance(a) == distance(b) && a < b); });
      roi.resize(static_cast<std::size_t>(spec.count));
      break;
    }
    case RoiSpec::Kind::set:
      for (int n : mesh.set(spec.set).nodes)
        if (std::binary_search(free.begin(), free.end(), n)) roi.push_back(n);
      break;
  }
  std::sort(roi.begin(), roi.end());
  if (roi.empty()) {
    std::string why;
    if (spec.kind == RoiSpec::Kind::ball) {
      const Vec3 low = mesh.nodes.rowwise().minCoeff(), high = mesh.nodes.rowwise().maxCoeff();
      if ((spec.center.array() < low.array()).any() || (spec.center.array() > high.array()).any())
        why = ": the centre lies outside the mesh's box, " + box_text(low, high);
      else if (spec.radius < 1 * mm)
        why = ": radius_mm is in millimetres, and " + number_text(spec.radius / mm) + " mm is smaller than any element (" +
              mesh.source + ")";
    }
    throw ModelError("the ROI (" + spec.describe() + ") contains no free node" + why);
  }
  return roi;
}

Partition partition_dofs(const SparseMatrix& K, const fem::DofMap& dofs, const std::vector<int>& roi_nodes) {
  Partition p;
  p.roi_nodes = roi_nodes;
  std::vector<char> in_roi(static_cast<std::size_t>(dofs.num_free()), 0);
  for (int n : roi_nodes)
    for (int c = 0; c < 3; ++c)
      if (const int i = dofs.free_dof(n, c); i >= 0) in_roi[static_cast<std::size_t>(i)] = 1;
  for (Index i = 0; i < dofs.num_free(); ++i) (in_roi[static_cast<std::size_t>(i)] ? p.d : p.s).push_back(i);
  // Interface: ROI dofs whose column of K has a static row.
  for (std::size_t k = 0; k < p.d.size(); ++k) {
    for (SparseMatrix::InnerIterator it(K, p.d[k]); it; ++it)
      if (!in_roi[static_cast<std::size_t>(it.row())] && it.value() != 0) {
        p.interface.push_back(static_cast<Index>(k));
        break;
      }
  }
  return p;
}

SparseMatrix submatrix(const SparseMatrix& K, const std::vector<Index>& rows, const std::vector<Index>& cols) {
  std::vector<int> row_map(static_cast<std::size_t>(K.rows()), -1);
  for (std::size_t k = 0; k < rows.size(); ++k) row_map[static_cast<std::size_t>(rows[k])] = static_cast<int>(k);
  SparseMatrix out(static_cast<Index>(rows.size()), static_cast<Index>(cols.size()));
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t j = 0; j < cols.size(); ++j)
    for (SparseMatrix::InnerIterator it(K, cols[j]); it; ++it)
      if (const int r = row_map[static_cast<std::size_t>(it.row())]; r >= 0)
        triplets.emplace_back(r, static_cast<int>(j), it.value());
  out.setFromTriplets(triplets.begin(), triplets.end());
  return out;
}

Vector gather(const Vector& v, const std::vector<Index>& indices) {
  Vector out(static_cast<Index>(indices.size()));
  for (std::size_t k = 0; k < indices.size(); ++k) out[static_cast<Index>(k)] = v[indices[k]];
  return out;
}

}  // namespace roifem::roi
