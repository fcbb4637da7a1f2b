// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/tissue_data.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/number_text.hpp"

namespace roifem::experiments {

namespace {

std::string trimmed(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(trimmed(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

const char* expected_header = "region,mode,deformation,nominal_stress_kPa (or nominal_stress_Pa)";

/// The stress column's scale to Pa, from its name; InputError if it names no unit.
double stress_unit(const std::string& where, const std::string& column) {
  if (column == "nominal_stress_kPa") return 1e3;
  if (column == "nominal_stress_Pa") return 1;
  if (column.rfind("nominal_stress", 0) == 0)
    throw InputError(where + ": column 4 '" + column +
                     "' states no unit the reader knows: name it nominal_stress_kPa or nominal_stress_Pa");
  throw InputError(where + ": column 4 is '" + column + "'; the columns are " + expected_header);
}

TissueMode mode_of(const std::string& where, const std::string& name) {
  if (name == "tension") return TissueMode::tension;
  if (name == "compression") return TissueMode::compression;
  if (name == "shear") return TissueMode::shear;
  throw InputError(where + ": mode '" + name + "' is none of tension, compression, shear");
}

double number_of(const std::string& where, const std::string& column, const std::string& text) {
  double x = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || error != std::errc() || end != text.data() + text.size())
    throw InputError(where + ": " + column + " '" + text + "' is not a number");
  if (!std::isfinite(x)) throw InputError(where + ": " + column + " is " + text + ", not a finite number");
  return x;
}

}  // namespace

std::string mode_name(TissueMode mode) {
  switch (mode) {
    case TissueMode::tension:
      return "tension";
    case TissueMode::compression:
      return "compression";
    case TissueMode::shear:
      return "shear";
  }
  return "?";
}

std::vector<TissueCurve> read_tissue_curves(const std::filesystem::path& file) {
  const std::string name = file.string();
  if (std::filesystem::is_directory(file)) throw InputError(name + ": is a directory, not a data file (.csv)");
  std::ifstream in(file);
  if (!in) throw InputError(name + ": no such data file, or it cannot be read");
  std::vector<TissueCurve> curves;
  std::map<std::pair<std::string, TissueMode>, int> first_line;  // of each curve, for messages
  double unit = 0;
  int line_number = 0;
  int last_line = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const std::string text = trimmed(line);
    if (text.empty() || text[0] == '#') continue;
    const std::string where = name + ":" + std::to_string(line_number);
    const auto fields = fields_of(text);
    if (unit == 0) {  // the header
      if (fields.size() != 4 || fields[0] != "region" || fields[1] != "mode" || fields[2] != "deformation")
        throw InputError(format("%s: the header is '%s'; the columns are %s", where.c_str(), text.c_str(), expected_header));
      unit = stress_unit(where, fields[3]);
      continue;
    }
    if (fields.size() != 4)
      throw InputError(where + ": " + std::to_string(fields.size()) + " fields; a row has 4 (" + expected_header + ")");
    if (fields[0].empty()) throw InputError(where + ": the region is empty");
    const TissueMode mode = mode_of(where, fields[1]);
    const double x = number_of(where, "deformation", fields[2]);
    const double stress = unit * number_of(where, "stress", fields[3]);
    if (mode == TissueMode::tension && x < 1)
      throw InputError(where + ": a tension row's stretch is " + fields[2] + ", below 1 (a compression row?)");
    if (mode == TissueMode::compression && (x > 1 || x <= 0))
      throw InputError(where + ": a compression row's stretch is " + fields[2] + ", outside (0, 1]");
    const bool continues = !curves.empty() && curves.back().region == fields[0] && curves.back().mode == mode;
    if (!continues) {
      if (const auto seen = first_line.find({fields[0], mode}); seen != first_line.end())
        throw InputError(where + ": region '" + fields[0] + "', " + fields[1] + ", began at line " +
                         std::to_string(seen->second) + " and was interrupted by other rows: give each curve as one run of rows");
      first_line[{fields[0], mode}] = line_number;
      curves.push_back({fields[0], mode, {}, {}});
    }
    TissueCurve& curve = curves.back();
    const std::size_t n = curve.deformation.size();
    if (n >= 1) {
      const double step = x - curve.deformation[n - 1];
      const double before = n >= 2 ? curve.deformation[n - 1] - curve.deformation[n - 2] : step;
      if (step == 0 || step * before < 0)
        throw InputError(where + ": region '" + fields[0] + "', " + fields[1] + ": the deformation " + fields[2] + " after " +
                         number_text(curve.deformation[n - 1]) + " is not monotone along the curve");
    }
    curve.deformation.push_back(x);
    curve.stress_Pa.push_back(stress);
    last_line = line_number;
  }
  if (unit == 0) throw InputError(name + ": no header (" + std::string(expected_header) + ")");
  if (curves.empty())
    throw InputError(name + ":" + std::to_string(std::max(last_line, line_number)) + ": no data rows after the header");
  return curves;
}

}  // namespace roifem::experiments
