// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Time-dependent loads as fixed spatial patterns times scalar ramps:
///   f(t) = sum_k r_k(t) p_k,   r_k(t) = min(t / T_k, 1)  (T_k = 0: a step at t = 0).
/// Keeping patterns and ramps apart lets static condensation transform each pattern once.
#include <memory>
#include <vector>

#include "common/types.hpp"

namespace roifem::model {

/// A rise from 0 at t = 0 to 1 at t = duration, then held: linear (the paper's load profile; its
/// rate jumps at both ends), or smooth, s^3 (10 - 15 s + 6 s^2) with s = t / duration (rate and
/// acceleration zero at both ends, continuous: a constrained DAE's multipliers stay finite).
/// Or sampled: piecewise linear through (t_i, r_i) from (0, 0), held after the last sample (a
/// tool's trajectory, one component per ramp; its kinks are the sample times).
struct Ramp {
  enum class Shape { linear, smooth, sampled };
  struct Samples {
    std::vector<double> t, value;  ///< t ascending from t_0 = 0, value_0 = 0
  };
  double duration = 0;  ///< s (sampled: the last sample's time)
  Shape shape = Shape::linear;
  std::shared_ptr<const Samples> samples;  ///< sampled only
  /// Piecewise linear through `samples`.
  static Ramp sampled(std::shared_ptr<const Samples> samples);
  double value(double t) const;
  /// d value / dt and d^2 value / dt^2 (1/s, 1/s^2); at a kink, the value after it.
  double rate(double t) const;
  double acceleration(double t) const;
  /// Where the rate jumps after t (the end of a linear ramp, a sampled one's sample times), ascending.
  std::vector<double> kinks_after(double t) const;
};

class LoadHistory {
 public:
  struct Term {
    Vector pattern;  ///< N, in the numbering of the system it loads
    Ramp ramp;
  };
  explicit LoadHistory(Index size = 0) : size_(size) {}
  void add(Vector pattern, Ramp ramp);
  /// f(t) into f (size() entries).
  void evaluate(double t, Eigen::Ref<Vector> f) const;
  Vector at(double t) const;
  Index size() const { return size_; }
  const std::vector<Term>& terms() const { return terms_; }
  /// The same patterns, every one with `ramp`.
  LoadHistory with_ramp(const Ramp& ramp) const {
    LoadHistory out = *this;
    for (auto& term : out.terms_) term.ramp = ramp;
    return out;
  }
  /// A history with every pattern mapped by `transform` (same ramps).
  template <class F>
  LoadHistory mapped(Index new_size, F&& transform) const {
    LoadHistory out(new_size);
    for (const auto& term : terms_) out.add(transform(term.pattern), term.ramp);
    return out;
  }

 private:
  Index size_;
  std::vector<Term> terms_;
};

}  // namespace roifem::model
