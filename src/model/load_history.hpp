#pragma once
/// Time-dependent loads as fixed spatial patterns times scalar ramps:
///   f(t) = sum_k r_k(t) p_k,   r_k(t) = min(t / T_k, 1)  (T_k = 0: a step at t = 0).
/// Keeping patterns and ramps apart lets static condensation transform each pattern once.
#include <vector>

#include "common/types.hpp"

namespace roifem::model {

/// A rise from 0 at t = 0 to 1 at t = duration, then held: linear (the paper's load profile; its
/// rate jumps at both ends), or smooth, s^3 (10 - 15 s + 6 s^2) with s = t / duration (rate and
/// acceleration zero at both ends, continuous: a constrained DAE's multipliers stay finite).
struct Ramp {
  enum class Shape { linear, smooth };
  double duration = 0;  ///< s
  Shape shape = Shape::linear;
  double value(double t) const;
  /// d value / dt and d^2 value / dt^2 (1/s, 1/s^2); at a kink, the value after it.
  double rate(double t) const;
  double acceleration(double t) const;
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
  LoadHistory with_ramp(Ramp ramp) const {
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
