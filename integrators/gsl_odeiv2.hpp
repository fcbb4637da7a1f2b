// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// GSL odeiv2 on the first-order form y = [u; v], y' = [v; M^-1 (f - C v - K u)], with the dense
/// Jacobian [[0, I], [-M^-1 K, -M^-1 C]] that GSL's implicit steppers need. Dense: the factory
/// refuses systems above max_gsl_dofs. Steppers: rk4 (fixed step), rk8pd, rk4imp, bsimp, msadams,
/// msbdf. Which of them take a fixed step, and which only adapt theirs, is the integrator
/// table's word (integrator_table.cpp): rk4 and rk4imp do both, the others adapt only.
#include <gsl/gsl_odeiv2.h>

#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "integrators/first_order_form.hpp"
#include "integrators/integrator.hpp"
#include "integrators/integrator_info.hpp"
#include "integrators/step_control.hpp"

namespace roifem::integrators {

inline constexpr Index max_gsl_dofs = 2000;  ///< of the second-order system (the first-order one is twice that)

/// The factory's maker for the table's GSL rows.
std::unique_ptr<Integrator> make_gsl(const IntegratorInfo& info, const gsl_odeiv2_step_type* stepper, const StepControl& control);
/// The table's rows of this family: GSL's steppers.
std::vector<IntegratorInfo> gsl_rows();

struct GslDriverDeleter {
  void operator()(gsl_odeiv2_driver* driver) const { gsl_odeiv2_driver_free(driver); }
};

class GslOdeiv2 final : public Integrator {
 public:
  GslOdeiv2(std::string name, const gsl_odeiv2_step_type* stepper, StepControl control);
  /// Refused states (an element inverted) in one output interval before the run stops (see rhs).
  static constexpr int max_refused_per_output = 25;
  std::string_view name() const override { return name_; }
  Stats stats() const override { return stats_; }
  /// The steppers that use no Jacobian (GSL's explicit ones) take a nonlinear model.
  bool takes_nonlinear() const override;

 private:
  void prepare(const model::SecondOrderSystem& system, const model::State& initial) override;
  void advance(double t_out, model::State& state) override;
  static int rhs(double t, const double y[], double dydt[], void* self);
  static int jacobian(double t, const double y[], double* dfdy, double dfdt[], void* self);

  std::string name_;
  const gsl_odeiv2_step_type* stepper_;
  StepControl control_;
  gsl_odeiv2_system system_gsl_{};
  std::unique_ptr<gsl_odeiv2_driver, GslDriverDeleter> driver_;
  const model::SecondOrderSystem* system_ = nullptr;
  std::unique_ptr<FirstOrderForm> form_;
  Vector y_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jacobian_;
  double t_ = 0;
  Stats stats_;
  std::exception_ptr pending_;
  std::string inadmissible_;  ///< the last state the model refused (guarded_recoverable_callback)
  int refused_ = 0;           ///< refused states in this advance
};

}  // namespace roifem::integrators
