// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A cutting blade and the tetrahedra it cuts. The blade is a straight edge from a to b (m) swept
/// along a path p (m) from its start time on: at time start + tau its edge runs from a + p(tau) to
/// b + p(tau). The path is piecewise linear (a straight move over a linear ramp, or a trajectory's
/// samples: model::ToolPath), so the surface the edge sweeps is a chain of parallelograms, each the
/// affine image X(s, sigma) = a + s (b - a) + p_0 + sigma (p_1 - p_0) of the unit square. A
/// tetrahedron's barycentric coordinates are affine in X, hence in (s, sigma): the part of a
/// parallelogram inside it is the unit square clipped by four half-planes, a convex polygon found
/// exactly, and the time the blade first reaches the tetrahedron is that polygon's least sigma.
#include <string>
#include <vector>

#include "common/types.hpp"
#include "mesh/tet_mesh.hpp"
#include "model/tools.hpp"

namespace roifem::cutting {

/// What a cut does to the tetrahedra its blade crosses.
enum class CutMode {
  remove,  ///< deletes them (element deletion, as SOFA's carving does)
  split,   ///< separates faces along the surface, removing no material (cutting/node_splitter.hpp)
};

/// One straight stretch of the sweep: the surface X(s, sigma) = origin + s edge + sigma move
/// (s, sigma in [0, 1]), which the blade covers between times t0 and t1 after its start.
struct SweptStrip {
  Vec3 origin, edge, move;
  double t0 = 0, t1 = 0;
};

struct Blade {
  std::string name;
  CutMode mode = CutMode::remove;
  Vec3 edge_a = Vec3::Zero(), edge_b = Vec3::Zero();  ///< m, the edge at the start
  double start = 0;                                   ///< s
  model::ToolPath path;                               ///< offsets from the start position (m), time from `start`
  std::string where;                                  ///< "file:line" of its [[cut]] table, for messages
  /// The path's corners, from 0 to the last (times after `start`, ascending): where it is straight between.
  std::vector<double> knots() const;
  /// The surface its edge sweeps, a strip per straight stretch of the path, in order.
  std::vector<SweptStrip> strips() const;
  /// When the blade stops: start + the last knot.
  double end() const;
  /// "cut 'name' (file:line)".
  std::string describe() const;
};

/// A tetrahedron the blade cuts, and the time it first reaches it (s).
struct Crossing {
  Index element = 0;
  double time = 0;
};

/// The tetrahedra whose interior the swept surface passes through, each with the time the blade
/// first reaches it, ascending by time (then by element). A surface that only grazes a tetrahedron
/// (through a vertex or an edge, or lying in a face's plane: the part inside it thinner than 1e-9
/// of its barycentric range) does not cut it. Throws InputError for a quadratic mesh, and for a
/// degenerate sweep: one whose area is below smallest_swept_area times the square of the mesh's
/// mean edge (an edge 1e-13 mm long, or one moving along itself, still removed tetrahedra).
std::vector<Crossing> swept_elements(const Blade& blade, const mesh::TetMesh& mesh);
inline constexpr double smallest_swept_area = 1e-6;
/// InputError naming the blade when its sweep's area is below smallest_swept_area times the mesh's
/// mean edge squared: both modes (swept_elements, separated_faces) refuse such a blade alike.
void refuse_a_degenerate_sweep(const Blade& blade, const mesh::TetMesh& mesh);

}  // namespace roifem::cutting
