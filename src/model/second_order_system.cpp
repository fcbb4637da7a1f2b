#include "model/second_order_system.hpp"

namespace roifem::model {

SparseMatrix diagonal_matrix(const Vector& d) {
  SparseMatrix D(d.size(), d.size());
  D.reserve(Eigen::VectorXi::Ones(d.size()));
  for (Index i = 0; i < d.size(); ++i) D.insert(i, i) = d[i];
  D.makeCompressed();
  return D;
}

double kinetic_energy(const SecondOrderSystem& sys, const State& s) { return 0.5 * s.v.dot(sys.M * s.v); }
double strain_energy(const SecondOrderSystem& sys, const State& s) { return 0.5 * s.u.dot(sys.K * s.u); }

}  // namespace roifem::model
