// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// A system with tools (model/tools.hpp) integrated by IDA as a constrained DAE: the tools' dofs
/// stay unknowns, held on their paths by Lagrange multipliers lambda (the tools' forces on their
/// nodes). H picks the tools' dofs; G(t) = S^T g(t) is where the paths put them. Three forms:
///   index 3      u' = v,  M v' + C v + K u = f + H^T lambda,  H u = G
///   GGL (index 2, Gear-Gupta-Leimkuhler): u' = v + H^T mu, the same, H u = G and H v = G'
///                (mu, a second multiplier, keeps u' on the velocity constraint)
///   index 1      the same with the constraint at acceleration level, Baumgarte-stabilized:
///                H v' - G'' + 2 a (H v - G') + a^2 (H u - G) = 0
/// y = [u; v; lambda (; mu)]: u, v differential, the multipliers algebraic (excluded from the
/// error test, as an index above 1 needs; with index 3 the tools' velocities too). Consistent initial values are computed, not
/// searched for: u = 0 but for the tools' nodes at G(t0), v = 0 but at G'(t0), the acceleration from the equation of motion and
/// lambda from the tools' rows. A linear ramp's end is a jump in G': the integration stops there and restarts from consistent
/// values (the DAE's own answer would be an impulse). The tools' force on the tissue, as elimination reports it (its nodes'
/// inertia moving with the tool), is S (lambda - M_pp G'' - C_pp G').
#include <exception>
#include <memory>
#include <string_view>
#include <vector>

#include "integrators/block_matrix.hpp"
#include "integrators/integrator.hpp"
#include "integrators/step_control.hpp"
#include "integrators/sundials/ida_solver.hpp"
#include "model/mass_inverse.hpp"
#include "model/prescribed_motion.hpp"

namespace roifem::integrators {

enum class ToolFormulation { index3, ggl, index1 };

/// "index3", "ggl", "index1" and back (InputError naming the three).
std::string_view formulation_name(ToolFormulation f);
ToolFormulation parse_formulation(std::string_view name);

class IdaToolDae {
 public:
  /// `all`: the system with the tools' dofs among its unknowns (M, C lumped at them: a full model,
  /// or one reduced with or without the static part's mass); `rtol`/`atol`
  /// from `control` (IDA's steps are error-controlled); `baumgarte_rate`: a (1/s), index 1 only.
  IdaToolDae(const model::SecondOrderSystem& all, const std::vector<model::ToolDofs>& tools, ToolFormulation formulation,
             StepControl control, double baumgarte_rate = 100.0);
  IdaToolDae(const IdaToolDae&) = delete;
  IdaToolDae& operator=(const IdaToolDae&) = delete;

  /// At rest at t0 but for the tools' nodes, which start on their paths with the path's velocity.
  void reset(double t0);
  /// Advances to t_out (stopping and restarting at the paths' kinks on the way).
  void advance_to(double t_out);
  double t() const { return t_; }
  /// Over all dofs of `all`.
  Vector displacement() const;
  Vector velocity() const;
  /// lambda: the force on each tool dof (N).
  Vector multipliers() const;
  /// Each tool's force on the tissue, S (lambda - M_pp G'' - C_pp G') (3 per tool).
  Vector tool_forces() const;
  /// max |H u - G| (m) and max |H v - G'| (m/s) now.
  double position_drift() const;
  double velocity_drift() const;
  Stats stats() const;

 private:
  void residual(double t, const Eigen::Ref<const Vector>& y, const Eigen::Ref<const Vector>& yp, Eigen::Ref<Vector> r);
  /// r += K u, or f_int(t, u) on a nonlinear model.
  void add_internal_force(double t, const Eigen::Ref<const Vector>& u, Eigen::Ref<Vector> r);
  /// dF/dy's blocks with K as the stiffness (the tangent on a nonlinear model), and dF/dy''s.
  std::vector<Block> dF_dy_blocks(const SparseMatrix& K) const;
  std::vector<Block> dF_dyp_blocks() const;
  /// A nonlinear model: dF/dy with the tangent at y (IDA's Jacobian setup asks for it).
  void update_dF_dy(double t, const Eigen::Ref<const Vector>& y);
  Index n() const { return all_.size(); }
  Index p() const { return H_.rows(); }
  /// G(t), G'(t), G''(t) over the tools' dofs.
  Vector path(double t, int derivative) const;
  /// Consistent y, y' at t from u_f, v_f (the dofs off the tools), into the solver's y and y'.
  void make_consistent(double t, const Vector& u, const Vector& v);
  /// Where the paths' and loads' rates jump after t, ascending, each once.
  std::vector<double> kinks_after(double t) const;

  const model::SecondOrderSystem& all_;
  ToolFormulation formulation_;
  StepControl control_;
  double a_;  ///< Baumgarte rate
  std::vector<model::Tool> tools_;
  std::vector<Index> tool_dofs_;
  std::vector<int> tool_component_;  ///< x, y or z of each tool dof
  std::vector<Index> tool_of_dof_;
  SparseMatrix H_, Ht_, S_, I_;
  std::vector<Index> sizes_;                          ///< the blocks of y: u, v, lambda (, mu)
  std::unique_ptr<model::MassInverse> mass_inverse_;  ///< for consistent accelerations
  SparseMatrix dF_dy_, dF_dyp_;
  Vector f_;
  Vector u_, f_int_;  ///< a nonlinear model's
  SparseMatrix K_t_;
  std::unique_ptr<sundials::IdaSolver> ida_;  ///< after the matrices it refers to
  double t_ = 0;
  std::vector<double> kinks_;  ///< after the reset's t0 (kinks_after), computed once: a sampled path has one per sample
  std::size_t next_kink_ = 0;  ///< the first of kinks_ not yet passed
};

}  // namespace roifem::integrators
