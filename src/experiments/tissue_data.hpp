// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Measured tissue curves (roifem fit's input): a CSV with the columns
///   region,mode,deformation,nominal_stress_kPa     (or nominal_stress_Pa)
/// one row per point: a region's name, the mode (tension, compression or shear), the stretch lambda
/// (tension, compression) or the amount of shear gamma (shear), and the nominal (first
/// Piola-Kirchhoff) stress. Lines starting with # are comments (the source, the units). Each
/// region's curve of each mode is one run of rows whose deformation is monotone.
#include <filesystem>
#include <string>
#include <vector>

namespace roifem::experiments {

enum class TissueMode { tension, compression, shear };
std::string mode_name(TissueMode mode);

struct TissueCurve {
  std::string region;
  TissueMode mode;
  std::vector<double> deformation;  ///< lambda (tension, compression) or gamma (shear), dimensionless
  std::vector<double> stress_Pa;    ///< nominal stress
};

/// The curves in file order (regions in the order they first appear). InputError naming the file
/// and line: a missing or wrong column, a stress column without a unit, an unknown mode, a number
/// that does not read or is not finite, a stretch on the wrong side of 1 for its mode, a curve whose
/// deformation is not monotone, or one region's rows split by another's.
std::vector<TissueCurve> read_tissue_curves(const std::filesystem::path& file);

}  // namespace roifem::experiments
