// SPDX-License-Identifier: GPL-3.0-or-later
#include "anatomy/surface_regions.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/errors.hpp"

namespace roifem::anatomy {

namespace {
std::vector<std::string> split(const std::string& text, char by) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, by)) parts.push_back(part);
  return parts;
}
RegionSpec check_name(const RegionSpec& region) {
  for (char c : region.name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
      throw InputError("--region '" + region.text + "': a set name may hold letters, digits, '_' and '-'");
  return region;
}

}  // namespace

RegionSpec parse_region(const std::string& text) {
  const std::string usage =
      "--region '" + text + "': expected NAME=sphere:X,Y,Z,RADIUS (mm), NAME=label:ATLAS_LABEL[,...] or NAME=below:Z (mm)";
  RegionSpec region;
  region.text = text;
  const auto equals = text.find('='), colon = text.find(':', equals == std::string::npos ? 0 : equals);
  if (equals == std::string::npos || equals == 0 || colon == std::string::npos) throw InputError(usage);
  region.name = text.substr(0, equals);
  const std::string kind = text.substr(equals + 1, colon - equals - 1);
  const std::vector<std::string> values = split(text.substr(colon + 1), ',');
  if (kind == "sphere" || kind == "below") {
    const std::size_t count = kind == "sphere" ? 4 : 1;
    if (values.size() != count) throw InputError(usage);
    double numbers[4];
    for (std::size_t i = 0; i < count; ++i) {
      std::size_t used = 0;
      try {
        numbers[i] = std::stod(values[i], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != values[i].size() || !std::isfinite(numbers[i]))
        throw InputError(usage + " ('" + values[i] + "' is not a number)");
    }
    if (kind == "below") {
      region.kind = RegionSpec::Kind::below;
      region.below_z_mm = numbers[0];
      return check_name(region);
    }
    region.centre_mm = {numbers[0], numbers[1], numbers[2]};
    region.radius_mm = numbers[3];
    if (!(region.radius_mm > 0)) throw InputError("--region '" + text + "': the radius must be positive");
  } else if (kind == "label") {
    if (values.empty()) throw InputError(usage);
    region.kind = RegionSpec::Kind::label;
    region.labels = values;
  } else {
    throw InputError(usage + " (unknown kind '" + kind + "')");
  }
  return check_name(region);
}

std::map<std::string, int> read_label_table(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot read the atlas's label table");
  std::map<std::string, int> table;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    int number = 0;
    std::string name;
    if (fields >> number >> name) table[name] = number;
  }
  if (table.empty()) throw InputError(file.string() + ": no '<number> <name>' lines in the atlas's label table");
  return table;
}

}  // namespace roifem::anatomy
