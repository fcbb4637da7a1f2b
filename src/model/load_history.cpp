// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/load_history.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::model {

namespace {

/// The sample interval holding t: i with t_i <= t < t_i+1 (the last one at or past the end).
std::size_t interval_of(const Ramp::Samples& s, double t) {
  const auto after = std::upper_bound(s.t.begin(), s.t.end(), t);
  return static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - s.t.begin() - 1, 0));
}

}  // namespace

Ramp Ramp::sampled(std::shared_ptr<const Samples> samples) {
  if (!samples || samples->t.size() < 2 || samples->t.size() != samples->value.size() || samples->t.front() != 0 ||
      samples->value.front() != 0)
    throw Error("internal: a sampled ramp needs two or more samples from (0, 0)");
  const double end = samples->t.back();
  return {.duration = end, .shape = Shape::sampled, .samples = std::move(samples)};
}

double Ramp::value(double t) const {
  if (shape == Shape::sampled) {
    if (t <= 0) return 0.0;
    const Samples& s = *samples;
    if (t >= s.t.back()) return s.value.back();
    const std::size_t i = interval_of(s, t);
    return s.value[i] + (s.value[i + 1] - s.value[i]) * (t - s.t[i]) / (s.t[i + 1] - s.t[i]);
  }
  if (t <= 0) return duration > 0 ? 0.0 : (t < 0 ? 0.0 : 1.0);
  if (duration <= 0 || t >= duration) return 1.0;
  const double s = t / duration;
  return shape == Shape::linear ? s : s * s * s * (10 - 15 * s + 6 * s * s);
}

double Ramp::rate(double t) const {
  if (t < 0 || duration <= 0 || t >= duration) return 0.0;
  if (shape == Shape::sampled) {
    const std::size_t i = interval_of(*samples, t);
    return (samples->value[i + 1] - samples->value[i]) / (samples->t[i + 1] - samples->t[i]);
  }
  const double s = t / duration;
  return (shape == Shape::linear ? 1.0 : 30 * s * s * (1 - s) * (1 - s)) / duration;
}

double Ramp::acceleration(double t) const {
  if (shape != Shape::smooth || t < 0 || duration <= 0 || t >= duration) return 0.0;
  const double s = t / duration;
  return 60 * s * (1 - s) * (1 - 2 * s) / (duration * duration);
}

std::vector<double> Ramp::kinks_after(double t) const {
  std::vector<double> kinks;
  if (shape == Shape::linear && duration > t) kinks.push_back(duration);
  if (shape == Shape::sampled)
    for (const double ti : samples->t)
      if (ti > t) kinks.push_back(ti);
  return kinks;
}

void LoadHistory::add(Vector pattern, Ramp ramp) {
  if (pattern.size() != size_) throw Error("internal: load pattern of the wrong size");
  if (!(ramp.duration >= 0)) throw InputError("load ramp duration " + number_text(ramp.duration) + " s must be >= 0");
  terms_.push_back({std::move(pattern), std::move(ramp)});
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
