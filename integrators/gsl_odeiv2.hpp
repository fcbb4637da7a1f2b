#pragma once
/// GSL odeiv2 on the first-order form y = [u; v], y' = [v; M^-1 (f - C v - K u)], with the dense
/// Jacobian [[0, I], [-M^-1 K, -M^-1 C]] that GSL's implicit steppers need. Dense: the factory
/// refuses systems above max_gsl_dofs. Steppers: rk4 (fixed step), rk8pd, rk4imp, bsimp, msadams,
/// msbdf (adaptive with rtol/atol; a fixed-step request runs every stepper at dt).
#include <gsl/gsl_odeiv2.h>

#include <exception>
#include <memory>

#include "integrators/arkode.hpp"  // StepControl
#include "integrators/integrator.hpp"
#include "model/mass_inverse.hpp"

namespace roifem::integrators {

inline constexpr Index max_gsl_dofs = 2000;  ///< of the second-order system (the first-order one is twice that)

class GslOdeiv2 final : public Integrator {
 public:
  GslOdeiv2(std::string name, const gsl_odeiv2_step_type* stepper, StepControl control);
  ~GslOdeiv2() override;
  std::string_view name() const override { return name_; }
  void reset(const model::SecondOrderSystem& system, const model::State& initial) override;
  void advance_to(double t_out, model::State& state) override;
  Stats stats() const override { return stats_; }

 private:
  static int rhs(double t, const double y[], double dydt[], void* self);
  static int jacobian(double t, const double y[], double* dfdy, double dfdt[], void* self);

  std::string name_;
  const gsl_odeiv2_step_type* stepper_;
  StepControl control_;
  gsl_odeiv2_system system_gsl_{};
  gsl_odeiv2_driver* driver_ = nullptr;
  const model::SecondOrderSystem* system_ = nullptr;
  std::unique_ptr<model::MassInverse> mass_inverse_;  // lumped, or full (Guyan, Craig-Bampton)
  Vector force_, work_, y_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jacobian_;
  double t_ = 0;
  Stats stats_;
  std::exception_ptr pending_;
};

}  // namespace roifem::integrators
