#include "model/load_history.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::model {

double Ramp::value(double t) const {
  if (t <= 0) return duration > 0 ? 0.0 : (t < 0 ? 0.0 : 1.0);
  if (duration <= 0 || t >= duration) return 1.0;
  const double s = t / duration;
  return shape == Shape::linear ? s : s * s * s * (10 - 15 * s + 6 * s * s);
}

double Ramp::rate(double t) const {
  if (t < 0 || duration <= 0 || t >= duration) return 0.0;
  const double s = t / duration;
  return (shape == Shape::linear ? 1.0 : 30 * s * s * (1 - s) * (1 - s)) / duration;
}

double Ramp::acceleration(double t) const {
  if (shape == Shape::linear || t < 0 || duration <= 0 || t >= duration) return 0.0;
  const double s = t / duration;
  return 60 * s * (1 - s) * (1 - 2 * s) / (duration * duration);
}

void LoadHistory::add(Vector pattern, Ramp ramp) {
  if (pattern.size() != size_) throw Error("internal: load pattern of the wrong size");
  if (!(ramp.duration >= 0)) throw InputError("load ramp duration " + number_text(ramp.duration) + " s must be >= 0");
  terms_.push_back({std::move(pattern), ramp});
}

void LoadHistory::evaluate(double t, Eigen::Ref<Vector> f) const {
  f.setZero();
  for (const auto& term : terms_)
    if (const double r = term.ramp.value(t); r != 0) f.noalias() += r * term.pattern;
}

Vector LoadHistory::at(double t) const {
  Vector f(size_);
  evaluate(t, f);
  return f;
}

}  // namespace roifem::model
