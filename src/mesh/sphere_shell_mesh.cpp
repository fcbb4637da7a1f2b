// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/sphere_shell_mesh.hpp"

#include <gmsh.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/gmsh_session.hpp"

namespace roifem::mesh {

TetMesh sphere_shell_octant_mesh(double a, double b, double h) {
  if (!(a > 0 && b > a))
    throw InputError("sphere shell: radii " + number_text(a) + " and " + number_text(b) + " m need 0 < a < b");
  if (!(h > 0 && h < b - a))
    throw InputError("sphere shell: element size " + number_text(h) + " m must lie in (0, b - a = " + number_text(b - a) + " m)");
  GmshSession session;
  return gmsh_call("sphere shell mesh", [&] {
    namespace occ = gmsh::model::occ;
    gmsh::model::add("shell");
    const int outer = occ::addSphere(0, 0, 0, b), inner = occ::addSphere(0, 0, 0, a);
    gmsh::vectorpair shell, octant;
    std::vector<gmsh::vectorpair> map;
    occ::cut({{3, outer}}, {{3, inner}}, shell, map);
    const int box = occ::addBox(0, 0, 0, 2 * b, 2 * b, 2 * b);
    occ::intersect(shell, {{3, box}}, octant, map);
    occ::synchronize();
    if (octant.size() != 1 || octant[0].first != 3) throw Error("internal: sphere shell geometry has an unexpected topology");
    gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {octant[0].second}), "shell");

    // The faces by their centres of mass: the planes have one coordinate 0, the spheres a radius.
    std::map<std::string, std::vector<int>> faces;
    gmsh::vectorpair surfaces;
    gmsh::model::getBoundary(octant, surfaces, false, false, false);
    const double eps = 1e-9 * b;
    for (const auto& [dim, tag] : surfaces) {
      double x, y, z;
      occ::getCenterOfMass(dim, tag, x, y, z);
      if (std::abs(x) < eps)
        faces["x0"].push_back(tag);
      else if (std::abs(y) < eps)
        faces["y0"].push_back(tag);
      else if (std::abs(z) < eps)
        faces["z0"].push_back(tag);
      else  // a spherical triangle's centre of mass lies inside its sphere: nearer a than b for the inner one
        faces[std::sqrt(x * x + y * y + z * z) < 0.5 * (a + b) ? "inner" : "outer"].push_back(tag);
    }
    for (const char* name : {"x0", "y0", "z0", "inner", "outer"}) {
      if (faces[name].size() != 1) throw Error(std::string("internal: sphere shell: expected one face ") + name);
      gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, faces[name]), name);
    }
    gmsh::option::setNumber("Mesh.MeshSizeMax", h);
    gmsh::option::setNumber("Mesh.MeshSizeMin", h);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay on one thread: the same mesh every time
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::model::mesh::generate(3);
    return extract_tet_mesh(
        "<sphere shell a = " + number_text(a) + " m, b = " + number_text(b) + " m, h = " + number_text(h) + " m>", 1.0);
  });
}

}  // namespace roifem::mesh
