// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Numeric types used throughout roifem. Units inside are SI (m, kg, s, N, Pa); see README.md.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SparseCore>

namespace roifem {

using Index = Eigen::Index;
using Vector = Eigen::VectorXd;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using DenseMatrix = Eigen::MatrixXd;
/// Column-major, 32-bit indices: enough for 2^31 non-zeros (a 300k-node brain has ~4e7).
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Lengths are stored in metres; files and the CLI speak millimetres.
inline constexpr double mm = 1e-3;

}  // namespace roifem
