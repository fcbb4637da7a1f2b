// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Element sizes for the next mesh of the same body, from an error estimate on this one
/// (fem/recovery_estimate.hpp): the mesh that spends a given number of nodes best spreads the error
/// evenly over its elements. With linear elements the energy error of an element of size h scales
/// as eta_e^2 ~ c_e h^(2p + 3) (p = 1; c_e the local smoothness), so equal shares at a fixed node
/// count ask for h_new ~ c_e^(-1 / (2p + 3)) = h_e (eta_e^2)^(-1 / (2p + 3)), up to one constant
/// (Zienkiewicz & Zhu 1987; Li & Bettess 1995). Near a singularity the local order is lower
/// than p, and the sizes keep shrinking from one pass to the next: each pass is bounded to
/// [1 / max_refinement, max_coarsening] times the present size, and a second pass carries on.
/// Per node the size is the volume-weighted geometric mean of its elements' sizes; neighbouring
/// nodes may differ by at most `gradation` times the edge between them (a mesher given a size that
/// jumps makes flat tetrahedra). The field is scaled so that a mesh following it holds as many
/// nodes as a uniform mesh of size 1 (int s^-3 dV = V), so that the caller's node-count search
/// starts from the uniform size.
#include <memory>

#include "common/types.hpp"
#include "mesh/point_locator.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::mesh {

struct SizeAdaptation {
  double order = 1;           ///< p, the element's polynomial order
  double max_refinement = 4;  ///< per pass
  double max_coarsening = 3;  ///< per pass
  double gradation = 0.35;    ///< largest size change per unit length
};

class AdaptedSizeField {
 public:
  /// `element_error2`: eta_e^2 per tetrahedron of `mesh` (any unit). Throws InputError when it
  /// does not match the mesh or holds a negative or non-finite value.
  AdaptedSizeField(TetMesh mesh, const Vector& element_error2, const SizeAdaptation& adaptation = {});

  /// The relative size at x (m), interpolated in the old mesh (its nearest boundary point outside).
  double relative_size(const Vec3& x) const;
  /// Per node of the old mesh, relative (int s^-3 dV = V).
  const Vector& nodal_size() const { return nodal_size_; }
  /// The size (m) of a uniform mesh with as many nodes: relative size 1.
  double uniform_size() const { return uniform_size_; }
  double smallest() const { return nodal_size_.minCoeff(); }
  double largest() const { return nodal_size_.maxCoeff(); }

 private:
  std::shared_ptr<const TetMesh> mesh_;  // the locator refers to it; shared so the field can move
  Vector nodal_size_;
  double uniform_size_ = 0;
  std::shared_ptr<const PointLocator> locator_;
};

}  // namespace roifem::mesh
