// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/xdmf.hpp"

#include <fstream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"

namespace roifem::io {

void write_xdmf(const std::filesystem::path& path, const XdmfSeries& s) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temporary_path());
    out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
        << "  <Grid Name=\"deformation\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    const bool varies = !s.topologies.empty();
    if (varies && (s.topologies.size() != s.times.size() || s.topology_tets.size() != s.times.size()))
      throw Error("internal: an XDMF series with a topology for some of its times only");
    for (std::size_t k = 0; k < s.times.size(); ++k) {
      const long tets = varies ? s.topology_tets[k] : s.tets;
      const std::string& topology = varies ? s.topologies[k] : s.tets_dataset;
      out << "   <Grid Name=\"t" << k << "\" GridType=\"Uniform\">\n"
          << "    <Time Value=\"" << s.times[k] << "\"/>\n"
          << "    <Topology TopologyType=\"" << (s.nodes_per_tet == 10 ? "Tetrahedron_10" : "Tetrahedron")
          << "\" NumberOfElements=\"" << tets << "\">\n"
          << "     <DataItem Dimensions=\"" << tets << " " << s.nodes_per_tet << "\" NumberType=\"Int\" Format=\"HDF\">"
          << s.h5_name << ":" << topology << "</DataItem>\n    </Topology>\n"
          << "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"" << s.nodes
          << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << s.h5_name << ":" << s.nodes_dataset
          << "</DataItem>\n    </Geometry>\n"
          << "    <Attribute Name=\"displacement_mm\" AttributeType=\"Vector\" Center=\"Node\">\n"
          << "     <DataItem Dimensions=\"" << s.nodes << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << s.h5_name
          << ":" << s.fields[k] << "</DataItem>\n    </Attribute>\n   </Grid>\n";
    }
    out << "  </Grid>\n </Domain>\n</Xdmf>\n";
    if (!out.flush()) throw InputError(path.string() + ": cannot write XDMF file");
  }
  file.commit();
}

}  // namespace roifem::io
