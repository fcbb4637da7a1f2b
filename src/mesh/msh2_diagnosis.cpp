// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/msh2_diagnosis.hpp"
#include "common/format.hpp"

#include <fstream>
#include <sstream>

namespace roifem::mesh {

namespace {

/// Reads a line, counting; false at the end of the file.
struct LineReader {
  std::ifstream in;
  long number = 0;
  std::string line;
  bool next() {
    if (!std::getline(in, line)) return false;
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }
};

/// A node line: tag x y z.
bool is_node(const std::string& line) {
  std::istringstream s(line);
  long tag = 0;
  double x = 0, y = 0, z = 0;
  std::string rest;
  return (s >> tag >> x >> y >> z) && !(s >> rest);
}

/// An element line: tag type ntags tag... node... (integers; at least one node).
bool is_element(const std::string& line) {
  std::istringstream s(line);
  long tag = 0, type = 0, ntags = 0, value = 0, count = 0;
  if (!(s >> tag >> type >> ntags) || ntags < 0) return false;
  while (s >> value) ++count;
  return s.eof() && count >= ntags + 1;
}

}  // namespace

std::string diagnose_msh2_ascii(const std::filesystem::path& file) {
  LineReader r{std::ifstream(file, std::ios::binary)};
  if (!r.next() || r.line != "$MeshFormat" || !r.next()) return "";
  std::istringstream format(r.line);
  std::string version;
  int file_type = -1;
  if (!(format >> version >> file_type) || !version.starts_with('2') || file_type != 0) return "";
  std::ostringstream what;
  while (r.next()) {
    if (r.line.empty() || r.line[0] != '$' || r.line.rfind("$End", 0) == 0) continue;
    const std::string section = r.line.substr(1);
    const bool nodes = section == "Nodes", elements = section == "Elements";
    long count = -1;
    if (nodes || elements) {
      if (!r.next()) break;
      std::istringstream header(r.line);
      if (!(header >> count) || count < 0) {
        what << r.number << ": expected the number of " << (nodes ? "nodes" : "elements") << ", got '" << r.line << "'";
        return what.str();
      }
      for (long k = 1; k <= count; ++k) {
        if (!r.next()) {
          what << r.number << ": the file ends inside $" << section << " after " << k - 1 << " of " << count << " "
               << (nodes ? "nodes" : "elements") << " (truncated?)";
          return what.str();
        }
        if (nodes ? !is_node(r.line) : !is_element(r.line)) {
          what << r.number << ": " << (nodes ? "node " : "element ") << k << " of " << count << ": expected '"
               << (nodes ? "tag x y z" : "tag type ntags tags... nodes...") << "', got '" << r.line << "'";
          return what.str();
        }
      }
    }
    bool ended = false;
    while (!ended && r.next()) ended = r.line == "$End" + section;
    if (!ended) {
      what << r.number << ": the file ends inside $" << section << " (no $End" << section << "; truncated?)";
      return what.str();
    }
  }
  return "";
}

}  // namespace roifem::mesh
