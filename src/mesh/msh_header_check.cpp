#include "mesh/msh_header_check.hpp"

#include <fstream>
#include <sstream>
#include <string>

#include "common/errors.hpp"

namespace roifem::mesh {

void check_msh_header_counts(const std::filesystem::path& file) {
  const auto bytes = static_cast<double>(std::filesystem::file_size(file));
  std::ifstream in(file, std::ios::binary);
  std::string line, version;
  long line_number = 0;
  auto refuse = [&](const std::string& section, double count) {
    std::ostringstream message;
    message.precision(15);
    message << file.string() << ":" << line_number << ": the " << section << " header claims " << count
            << " entries, more than the file's " << bytes << " bytes could hold (a corrupt or truncated file)";
    throw InputError(message.str());
  };
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "$MeshFormat") {
      if (!std::getline(in, version)) return;
      ++line_number;
    } else if (line == "$Nodes" || line == "$Elements") {
      const std::string section = line;
      if (!std::getline(in, line)) return;
      ++line_number;
      std::istringstream header(line);
      double first = 0, second = 0;
      if (version.rfind("4", 0) == 0) {  // MSH 4: numEntityBlocks numEntries minTag maxTag
        if (!(header >> first >> second)) return;  // binary 4.1 headers are not text: Gmsh checks those
        if (first > bytes) refuse(section + " (entity blocks)", first);
        if (second > bytes) refuse(section, second);
      } else {  // MSH 2: the count alone
        if (!(header >> first)) return;
        if (first > bytes) refuse(section, first);
      }
    }
  }
}

}  // namespace roifem::mesh
