// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/msh_header_check.hpp"
#include "common/format.hpp"

#include <array>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include "common/errors.hpp"

namespace roifem::mesh {

void check_msh_header_counts(const std::filesystem::path& file) {
  const auto bytes = static_cast<double>(std::filesystem::file_size(file));
  std::ifstream in(file, std::ios::binary);
  std::string line, version;
  int file_type = 0, data_size = 0;  // from "$MeshFormat": version file-type (1: binary) data-size
  bool little_endian_ones = false;   // binary files follow it with the int 1, in the writer's byte order
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
      if (!std::getline(in, line)) return;
      ++line_number;
      std::istringstream format(line);
      format >> version >> file_type >> data_size;
      if (file_type == 1) {
        std::array<unsigned char, 4> one{};
        in.read(reinterpret_cast<char*>(one.data()), 4);
        little_endian_ones = in && one == std::array<unsigned char, 4>{1, 0, 0, 0};
      }
    } else if (version.starts_with('4') && file_type == 1 && (line == "$Nodes" || line == "$Elements")) {
      // MSH 4 binary: numEntityBlocks numEntries minTag maxTag as data-size unsigned integers.
      if (!little_endian_ones || data_size != 8) return;  // another writer's byte order: Gmsh checks those
      std::array<std::uint64_t, 2> counts{};
      std::array<unsigned char, 16> raw{};
      if (!in.read(reinterpret_cast<char*>(raw.data()), raw.size())) return;
      for (std::size_t k = 0; k < 2; ++k)
        for (int b = 7; b >= 0; --b) counts[k] = counts[k] << 8 | raw[8 * k + static_cast<std::size_t>(b)];
      if (static_cast<double>(counts[0]) > bytes) refuse(line + " (entity blocks)", static_cast<double>(counts[0]));
      if (static_cast<double>(counts[1]) > bytes) refuse(line, static_cast<double>(counts[1]));
    } else if (line == "$Nodes" || line == "$Elements") {
      const std::string section = line;
      if (!std::getline(in, line)) return;
      ++line_number;
      std::istringstream header(line);
      double first = 0, second = 0;
      if (version.starts_with('4')) {  // MSH 4: numEntityBlocks numEntries minTag maxTag
        if (!(header >> first >> second)) return;
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
