// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The element size for a wanted node count, for mesh generators whose count N(h) falls roughly
/// as h^slope (Gmsh's brain, CGAL's image brains). Each trial's count refines a secant on log N
/// against log h (the slope measured between the last two trials, kept within [-4, -1]); the next
/// size stays inside the bracket [a size that gave too many nodes, one that gave too few] and is
/// their geometric mean when the secant would leave it. N(h) is a staircase: when the bracket
/// closes to 0.1% without a hit, its steps jump over the target (stuck()).
namespace roifem::mesh {

class NodeCountSearch {
 public:
  NodeCountSearch(double target_nodes, double first_size, double slope) : target_(target_nodes), h_(first_size), slope_(slope) {}

  /// The size to try next.
  double size() const { return h_; }
  /// Records the count size() gave: true when it lies within `tolerance` (relative) of the
  /// target; otherwise moves size() on, unless the search is stuck.
  bool record(double nodes, double tolerance);
  bool stuck() const { return h_fine_ > 0 && h_coarse_ > 0 && h_coarse_ / h_fine_ - 1 < 1e-3; }

 private:
  double target_, h_, slope_;
  double prev_h_ = 0, prev_n_ = 0;
  double h_fine_ = 0, h_coarse_ = 0;  ///< the bracket: h_fine_ gave too many nodes, h_coarse_ too few
};

}  // namespace roifem::mesh
