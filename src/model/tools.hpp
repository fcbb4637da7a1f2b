// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Rigid tools that move tissue (the paper's spatulas, a surgeon's instrument): a tool is attached
/// to a set of nodes, all three components, and prescribes their displacement, g(t) (bilateral).
/// A ToolSet describes the tools of a system whose unknowns they drive (the tool's own dofs are not
/// among them: prescribed_motion.hpp eliminates them), and gives per tool
///   F(t) = coupling u + self G(t) - f_tools(t)       (N, on the tissue),
/// the residual K u - f summed over its attached nodes: the force the tool applies to the tissue
/// (the surgeon feels -F). The attached nodes' own inertia moves with the tool, so that the energy
/// of the tissue obeys, exactly for the trapezoidal rule,
///   E + D = W_loads + W_tools,   W_tools = integral of F . dg/dt,
/// with the coupling energy g . coupling u + g . self g / 2 counted in the strain energy.
/// On a nonlinear model the set holds its law (model/internal_force.hpp), and F gains what the
/// law's elements at the tools' nodes give beyond their linear stiffness.
/// Vectors over the tools stack each tool's x, y, z (3 T entries).
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "model/load_history.hpp"

namespace roifem::model {

class InternalForce;  // internal_force.hpp

/// The tool's rigid translation g(t) (m): displacement ramp(t), or a trajectory, piecewise linear
/// through sampled points (one sampled ramp per component, in metres).
struct ToolPath {
  Vec3 displacement = Vec3::Zero();  ///< reached at the end of the ramp
  Ramp ramp;
  std::optional<std::array<Ramp, 3>> trajectory;  ///< set: g_c(t) = trajectory[c].value(t) instead
  std::string trajectory_file;                    ///< where the trajectory was read
  Vec3 at(double t) const { return component(t, &Ramp::value); }
  Vec3 velocity(double t) const { return component(t, &Ramp::rate); }
  Vec3 acceleration(double t) const { return component(t, &Ramp::acceleration); }
  /// g(t) as a sum of fixed directions times histories: (displacement, ramp), or (e_c, trajectory_c).
  std::vector<std::pair<Vec3, Ramp>> terms() const;
  /// Where g' jumps after t, ascending.
  std::vector<double> kinks_after(double t) const;

 private:
  Vec3 component(double t, double (Ramp::*f)(double) const) const {
    if (!trajectory) return (ramp.*f)(t)*displacement;
    return {((*trajectory)[0].*f)(t), ((*trajectory)[1].*f)(t), ((*trajectory)[2].*f)(t)};
  }
};

struct Tool {
  std::string name;
  std::vector<int> nodes;  ///< mesh nodes it holds, ascending
  ToolPath path;
};

class ToolSet {
 public:
  ToolSet() = default;
  /// coupling: 3T x n, each tool's rows of K summed over its nodes, at the unknowns; self: 3T x 3T,
  /// the same at the tools' own dofs (the force of a unit translation of each tool); load_at_tools:
  /// the loads (3T entries per pattern) on the attached nodes, with their ramps.
  ToolSet(std::vector<Tool> tools, const SparseMatrix& coupling, DenseMatrix self, LoadHistory load_at_tools);

  bool empty() const { return tools_.empty(); }
  Index count() const { return static_cast<Index>(tools_.size()); }
  const std::vector<Tool>& tools() const { return tools_; }
  /// g(t) of every tool (3T).
  Vector positions(double t) const;
  /// F(t) of every tool (3T) for the unknowns u.
  Vector forces(const Eigen::Ref<const Vector>& u, double t) const;
  /// The same from the products the caller has formed: coupling u and self g (the energy ledger's).
  Vector forces(const Vector& coupled, const Vector& self_g, const Eigen::Ref<const Vector>& u, double t) const;
  /// The same tools on a nonlinear model whose law (over the same unknowns) moves their nodes.
  ToolSet with_law(std::shared_ptr<const InternalForce> law) const;
  /// The loads on the attached nodes, summed per tool (3T): f_tools(t).
  Vector loads_at_tools(double t) const { return load_at_tools_.at(t); }
  /// coupling x (3T): how the unknowns pull on the tools.
  Vector coupling_times(const Eigen::Ref<const Vector>& x) const { return coupling_ * x; }
  /// self g (3T): the tools' pull on themselves at positions g.
  Vector self_times(const Eigen::Ref<const Vector>& g) const { return self_ * g; }
  /// The strain energy stored between the tools and the unknowns: g . coupling u + g . self g / 2.
  double coupling_energy(const Eigen::Ref<const Vector>& u, double t) const;
  /// The same tools for a system whose unknown new_index[i] is this one's unknown i (all mapped),
  /// without a law (that system's is another: with_law).
  ToolSet renumbered(Index new_size, const std::vector<Index>& new_index) const;
  /// The same tools with every path's ramp, and every load at the tools, on `ramp` (as
  /// LoadHistory::with_ramp does for the system the tools drive), the law's too. Throws Error for a
  /// trajectory.
  ToolSet with_ramp(const Ramp& ramp) const;
  const SparseMatrix& coupling() const { return coupling_; }

 private:
  std::vector<Tool> tools_;
  SparseMatrix coupling_;
  DenseMatrix self_;
  LoadHistory load_at_tools_;
  std::shared_ptr<const InternalForce> law_;  ///< null: the linear model
};

}  // namespace roifem::model
