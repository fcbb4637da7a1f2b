// SPDX-License-Identifier: GPL-3.0-or-later
// msh_convert IN OUT VERSION BINARY: rewrites a Gmsh mesh file in MSH VERSION (2.2 or 4.1), ASCII
// (BINARY = 0) or binary (1), through Gmsh itself. The bad-input tests make their binary and
// MSH 4.1 fixtures with it from one ASCII MSH 2.2 file.
#include <gmsh.h>

#include <cstdio>
#include <exception>
#include <string>

#include "mesh/gmsh_session.hpp"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: msh_convert IN OUT VERSION BINARY\n");
    return 2;
  }
  try {
    const roifem::mesh::GmshSession session;
    roifem::mesh::gmsh_call(argv[1], [&] {
      gmsh::open(argv[1]);
      gmsh::option::setNumber("Mesh.MshFileVersion", std::stod(argv[3]));
      gmsh::option::setNumber("Mesh.Binary", std::stoi(argv[4]));
      gmsh::option::setNumber("Mesh.SaveAll", 0);
      gmsh::write(argv[2]);
    });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "msh_convert: %s\n", e.what());
    return 1;
  }
  return 0;
}
