// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Named surface regions of an anatomical mesh, chosen by a point and radius in the image's
/// millimetres (MNI for the Colin27 template) or by atlas labels (AAL's region names or numbers).
///   "motor=label:Precentral_R"        the boundary faces over the atlas region(s), ',' between several
///   "target=sphere:30,-20,70,15"      the boundary faces whose centres lie within 15 mm of the point
///   "base=below:-42"                  the boundary faces whose centres lie below z = -42 mm (where the
///                                     skull base carries the brain)
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace roifem::anatomy {

struct RegionSpec {
  std::string name, text;  ///< text: the option as given, for messages
  enum class Kind { sphere, label, below } kind = Kind::sphere;
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();
  double radius_mm = 0;
  double below_z_mm = 0;
  std::vector<std::string> labels;  ///< names or numbers, resolved against the atlas's table
};

/// Parses "NAME=sphere:X,Y,Z,R", "NAME=label:L1[,L2...]" or "NAME=below:Z"; InputError quoting
/// `text` otherwise.
RegionSpec parse_region(const std::string& text);

/// An atlas's label table: "<number> <name> ..." per line, as mricron ships beside aal.nii.gz
/// (aal.nii.txt). Throws InputError naming the file if it cannot be read.
std::map<std::string, int> read_label_table(const std::filesystem::path& file);

}  // namespace roifem::anatomy
