#include "model/spectrum.hpp"

#include <Spectra/SymEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "common/errors.hpp"

namespace roifem::model {

namespace {

/// y = D K D x with D = M^-1/2 (diagonal): the operator Spectra iterates with.
class ScaledStiffness {
 public:
  using Scalar = double;
  ScaledStiffness(const SecondOrderSystem& system, Vector scale)
      : system_(system), scale_(std::move(scale)), x_(scale_.size()), y_(scale_.size()) {}
  Index rows() const { return scale_.size(); }
  Index cols() const { return scale_.size(); }
  void perform_op(const double* in, double* out) const {
    x_ = scale_.cwiseProduct(Eigen::Map<const Vector>(in, rows()));
    system_.apply_stiffness(x_, y_);
    Eigen::Map<Vector>(out, rows()) = scale_.cwiseProduct(y_);
  }

 private:
  const SecondOrderSystem& system_;
  Vector scale_;
  mutable Vector x_, y_;
};

}  // namespace

double highest_frequency(const SecondOrderSystem& system, double tolerance) {
  const Index n = system.size();
  const SparseMatrix& M = system.M;
  if (n == 0) throw InputError("highest frequency: the system has no dofs");
  if (M.nonZeros() != n || Vector(M.diagonal()).minCoeff() <= 0)
    throw InputError("highest frequency: needs a diagonal (lumped), positive mass matrix");
  const Vector scale = Vector(M.diagonal()).cwiseSqrt().cwiseInverse();
  if (n <= 20) {  // too small for a Krylov space: dense
    const DenseMatrix A = scale.asDiagonal() * DenseMatrix(system.K) * scale.asDiagonal();
    return std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<DenseMatrix>(A, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff()));
  }
  ScaledStiffness op(system, scale);
  Spectra::SymEigsSolver<ScaledStiffness> lanczos(op, 1, std::min<Index>(n, 20));
  lanczos.init();
  lanczos.compute(Spectra::SortRule::LargestAlge, 1000, tolerance);
  if (lanczos.info() != Spectra::CompInfo::Successful)
    throw SolverError("highest frequency: Lanczos did not converge in 1000 restarts (" + std::to_string(lanczos.num_operations()) +
                      " products with K)");
  return std::sqrt(std::max(0.0, lanczos.eigenvalues()[0]));
}

}  // namespace roifem::model
