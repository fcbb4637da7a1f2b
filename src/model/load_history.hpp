#pragma once
/// Time-dependent loads as fixed spatial patterns times scalar ramps:
///   f(t) = sum_k r_k(t) p_k,   r_k(t) = min(t / T_k, 1)  (T_k = 0: a step at t = 0).
/// Keeping patterns and ramps apart lets static condensation transform each pattern once.
#include <vector>

#include "common/types.hpp"

namespace roifem::model {

/// Linear rise from 0 at t = 0 to 1 at t = duration, then held (the paper's load profile).
struct Ramp {
  double duration = 0;  ///< s
  double value(double t) const;
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
