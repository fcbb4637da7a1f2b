#include "model/mass_inverse.hpp"

#include "common/errors.hpp"

namespace roifem::model {

bool is_diagonal(const SparseMatrix& A) {
  for (Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() != it.col() && it.value() != 0) return false;
  return true;
}

MassInverse::MassInverse(const SparseMatrix& M) {
  if (model::is_diagonal(M)) {
    const Vector m = M.diagonal();
    if (!(m.size() == 0 || m.minCoeff() > 0)) throw ModelError("mass matrix: a non-positive diagonal entry");
    inverse_diagonal_ = m.cwiseInverse();
    return;
  }
  factor_ = std::make_unique<solvers::Cholesky>();
  try {
    factor_->compute(M);
  } catch (const solvers::NotPositiveDefinite& e) {
    throw ModelError(std::string("mass matrix is not positive definite: ") + e.what());
  }
}

void MassInverse::apply(const Eigen::Ref<const Vector>& b, Eigen::Ref<Vector> x) const {
  if (factor_)
    factor_->solve(b, x);
  else
    x = inverse_diagonal_.cwiseProduct(b);
}

DenseMatrix MassInverse::apply(const DenseMatrix& B) const {
  return factor_ ? factor_->solve_matrix(B) : DenseMatrix(inverse_diagonal_.asDiagonal() * B);
}

}  // namespace roifem::model
