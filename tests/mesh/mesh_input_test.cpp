// SPDX-License-Identifier: GPL-3.0-or-later
// Reading meshes, and every kind of bad mesh input stopping with a message that names the fault.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>

#include "common/errors.hpp"
#include "mesh/brain_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh/msh2_diagnosis.hpp"
#include "test_support.hpp"

namespace roifem::mesh {
namespace {

using test::TempDir;
using test::write_file;

std::string error_of(auto&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}

TEST(MeshReader, ReadsTheShippedBrainWithItsNamedSets) {
  const TetMesh mesh = read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  check_mesh(mesh);
  EXPECT_EQ(mesh.set("brain").tets.size(), mesh.tets.size());
  EXPECT_EQ(mesh.set("brain").nodes.size(), static_cast<std::size_t>(mesh.num_nodes()));
  EXPECT_FALSE(mesh.set("opening_left").triangles.empty());
  // The base is the lowest 15% of the height: z <= -50 + 15 mm.
  for (int n : mesh.set("base").nodes) EXPECT_LE(mesh.nodes(2, n), -0.035 + 1e-9);
  // Walls of the opening are the planes x = -2 mm and x = +2 mm.
  for (int n : mesh.set("opening_left").nodes) EXPECT_NEAR(mesh.nodes(0, n), -0.002, 1e-9);
  for (int n : mesh.set("opening_right").nodes) EXPECT_NEAR(mesh.nodes(0, n), 0.002, 1e-9);
}

TEST(MeshReader, LeavesOpenMPsThreadCountAsItFoundIt) {
  // Gmsh sets OpenMP's thread count to its General.NumThreads (1) when it starts: every OpenMP
  // loop after a mesh was read (the stiffness assembly, the haptic tick's law) ran on one thread.
  const int before = omp_get_max_threads();
  omp_set_num_threads(3);
  (void)read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  EXPECT_EQ(omp_get_max_threads(), 3);
  omp_set_num_threads(before);
}

TEST(MeshReader, ReadsMsh22AndScalesLengths) {
  TempDir dir;
  const auto file = write_file(dir / "tet.msh", test::single_tet_msh(test::unit_tet_nodes, "1 2 3 4"));
  const TetMesh mesh = read_mesh(file, 1e-3);
  ASSERT_EQ(mesh.num_tets(), 1);
  EXPECT_NEAR(total_volume(mesh), 1e-9 / 6, 1e-22);
}

TEST(MeshReader, MissingFileIsNamed) {
  EXPECT_NE(error_of([] { read_mesh("/nonexistent/brain.msh"); }).find("/nonexistent/brain.msh: no such mesh file"),
            std::string::npos);
}

TEST(MeshReader, EmptyFileIsNamed) {
  TempDir dir;
  const auto file = write_file(dir / "empty.msh", "");
  EXPECT_NE(error_of([&] { read_mesh(file); }).find("empty.msh: the mesh file is empty"), std::string::npos);
}

TEST(MeshReader, GarbageFileIsNamedWithItsLine) {
  TempDir dir;
  const auto file = write_file(dir / "garbage.msh", "this is not a mesh\n");
  const std::string msg = error_of([&] { read_mesh(file); });
  EXPECT_NE(msg.find("garbage.msh"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 1"), std::string::npos) << msg;
}

TEST(MeshReader, TruncatedFileIsNamed) {
  TempDir dir;
  const std::string full = test::single_tet_msh(test::unit_tet_nodes, "1 2 3 4");
  const auto file = write_file(dir / "truncated.msh", full.substr(0, full.find("3 0 1 0")));
  const std::string msg = error_of([&] { read_mesh(file); });
  EXPECT_NE(msg.find("truncated.msh"), std::string::npos) << msg;
}

TEST(MeshReader, TruncatedOrMalformedMsh2NamesTheLine) {
  // Gmsh says only "Error loading" for these; the line at fault is found after it fails.
  TempDir dir;
  const std::string full = test::single_tet_msh(test::unit_tet_nodes, "1 2 3 4");
  auto message = [&](const std::string& name, const std::string& text) {
    return error_of([&] { read_mesh(write_file(dir / name, text)); });
  };
  std::string msg = message("cut.msh", full.substr(0, full.find("3 0 1 0")));
  EXPECT_NE(msg.find("cut.msh:7: the file ends inside $Nodes after 2 of 4 nodes (truncated?)"), std::string::npos) << msg;
  std::string bad = full;
  bad.replace(bad.find("3 0 1 0"), 7, "3 0 one 0");
  msg = message("node.msh", bad);
  EXPECT_NE(msg.find("node.msh:8: node 3 of 4: expected 'tag x y z', got '3 0 one 0'"), std::string::npos) << msg;
  bad = full;
  bad.replace(bad.find("1 4 2 1 1 1 2 3 4"), 17, "1 4 2 1 1 1 2 3 x");
  msg = message("element.msh", bad);
  EXPECT_NE(msg.find("element.msh:13: element 1 of 1: expected"), std::string::npos) << msg;
  EXPECT_EQ(diagnose_msh2_ascii(write_file(dir / "good.msh", full)), "");
}

TEST(MeshReader, TruncatedShippedBrainIsNamed) {
  TempDir dir;
  std::ifstream in(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto file = write_file(dir / "cut.msh", text.substr(0, text.size() / 2));
  EXPECT_NE(error_of([&] { read_mesh(file); }).find("cut.msh"), std::string::npos);
}

TEST(MeshReader, FileWithoutTetrahedraIsNamed) {
  TempDir dir;
  const auto file = write_file(dir / "surface.msh",
                               "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                               "$Elements\n1\n1 2 2 1 1 1 2 3\n$EndElements\n");
  EXPECT_NE(error_of([&] { read_mesh(file); }).find("surface.msh: the mesh has no tetrahedra"), std::string::npos);
}

TEST(MeshChecks, InvertedTetrahedronIsNamedByIndex) {
  TempDir dir;
  const auto file = write_file(dir / "inverted.msh", test::single_tet_msh(test::unit_tet_nodes, "1 3 2 4"));
  const TetMesh mesh = read_mesh(file);
  const std::string msg = error_of([&] { check_mesh(mesh); });
  EXPECT_NE(msg.find("inverted.msh: tetrahedron 0"), std::string::npos) << msg;
  EXPECT_NE(msg.find("inverted"), std::string::npos) << msg;
}

TEST(MeshChecks, ZeroVolumeTetrahedronIsNamedByIndex) {
  TempDir dir;
  const auto file = write_file(dir / "flat.msh", test::single_tet_msh("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 1 1 0\n", "1 2 3 4"));
  const TetMesh mesh = read_mesh(file);
  const std::string msg = error_of([&] { check_mesh(mesh); });
  EXPECT_NE(msg.find("tetrahedron 0"), std::string::npos) << msg;
  EXPECT_NE(msg.find("zero volume"), std::string::npos) << msg;
}

// Found by fuzzing: a tetrahedron whose four nodes coincide has quality 0/0 = NaN, which passed a
// "q < threshold" test; and one naming a node that does not exist.
TEST(MeshChecks, CoincidentNodesAndMissingNodesAreNamed) {
  TetMesh mesh;
  mesh.nodes = Eigen::Matrix3Xd::Zero(3, 4);
  mesh.nodes.col(1) = Vec3(1, 0, 0);
  mesh.nodes.col(2) = Vec3(0, 1, 0);
  mesh.nodes.col(3) = Vec3(0, 0, 1);
  mesh.tets = {{0, 0, 0, 0}};
  std::string msg = error_of([&] { check_mesh(mesh); });
  EXPECT_NE(msg.find("tetrahedron 0 (nodes 0, 0, 0, 0, 0-based) has zero volume"), std::string::npos) << msg;
  mesh.tets = {{0, 1, 2, 7}};
  msg = error_of([&] { check_mesh(mesh); });
  EXPECT_NE(msg.find("names node 7, but the mesh has 4 nodes"), std::string::npos) << msg;
  mesh.tets = {{0, 1, 2, 3}};
  mesh.nodes *= 1e300;  // volume overflows
  msg = error_of([&] { check_mesh(mesh); });
  EXPECT_NE(msg.find("volume overflows"), std::string::npos) << msg;
}

TEST(MeshChecks, CoincidentNodesAreASeamNamedByBothNodes) {
  // Two tetrahedra on either side of the face (1, 2, 3), the second given its own copies of the
  // face's nodes (tags 5, 6, 7): a seam. Sharing the nodes instead passes.
  TempDir dir;
  const std::string nodes = "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 0 0 0\n6 1 0 0\n7 0 1 0\n8 0 0 -1\n";
  auto two_tets = [&](const std::string& second) {
    return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n" + nodes +
           "$EndNodes\n$Elements\n2\n1 4 2 1 1 1 2 3 4\n2 4 2 1 1 " + second + "\n$EndElements\n";
  };
  const TetMesh seam = read_mesh(write_file(dir / "seam.msh", two_tets("5 7 6 8")));
  const std::string msg = error_of([&] { check_mesh(seam); });
  EXPECT_NE(msg.find("seam.msh: nodes 0 and 4 (0-based) coincide at (0, 0, 0) mm"), std::string::npos) << msg;
  const TetMesh shared = read_mesh(write_file(dir / "shared.msh", two_tets("1 3 2 8")));
  EXPECT_NO_THROW(check_mesh(shared));
  // Near but not within 1e-10 of the diagonal: two distinct points.
  TetMesh close = shared;
  close.nodes.conservativeResize(3, close.num_nodes() + 1);
  const double diagonal = (shared.nodes.rowwise().maxCoeff() - shared.nodes.rowwise().minCoeff()).norm();
  close.nodes.col(close.num_nodes() - 1) = close.nodes.col(0) + Vec3(1e-9 * diagonal, 0, 0);
  EXPECT_NO_THROW(check_mesh(close));
  close.nodes.col(close.num_nodes() - 1) = close.nodes.col(0) + Vec3(1e-11 * diagonal, 0, 0);
  EXPECT_NE(error_of([&] { check_mesh(close); }).find("coincide"), std::string::npos);
}

TEST(MeshSets, MissingNamedSetListsTheExistingOnes) {
  const TetMesh mesh = read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh");
  const std::string msg = error_of([&] { mesh.set("skull"); });
  EXPECT_NE(msg.find("no named set 'skull'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("opening_left"), std::string::npos) << msg;
}

TEST(BrainMesh, GeneratesTheRequestedNodeCountAndWritesAReadableFile) {
  TempDir dir;
  const BrainMesh generated = generate_brain_mesh(2000, dir / "brain.msh");
  EXPECT_NEAR(static_cast<double>(generated.mesh.num_nodes()), 2000.0, 0.05 * 2000);
  const TetMesh reread = read_mesh(dir / "brain.msh");
  EXPECT_EQ(reread.num_nodes(), generated.mesh.num_nodes());
  EXPECT_EQ(reread.num_tets(), generated.mesh.num_tets());
  check_mesh(reread);
  // Only the final file is left behind: no temporary.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

/// The mean edge length (m) of the tetrahedra with a node on one of the slit's walls.
double mean_edge_at_the_slit(const TetMesh& m) {
  std::vector<char> on_wall(static_cast<std::size_t>(m.num_nodes()), 0);
  for (const char* set : {"opening_left", "opening_right"})
    for (int n : m.set(set).nodes) on_wall[static_cast<std::size_t>(n)] = 1;
  double sum = 0;
  int edges = 0;
  for (const Tet& t : m.tets) {
    if (!std::any_of(t.begin(), t.end(), [&](int n) { return on_wall[static_cast<std::size_t>(n)] != 0; })) continue;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b, ++edges)
        sum += (m.node(t[static_cast<std::size_t>(a)]) - m.node(t[static_cast<std::size_t>(b)])).norm();
  }
  return sum / edges;
}

TEST(BrainMesh, SlitRefinementShrinksTheElementsAtTheOpeningAtTheSameNodeCount) {
  BrainShape graded;
  graded.slit_refinement = 0.25;
  const TetMesh uniform = generate_brain_mesh(2000).mesh, refined = generate_brain_mesh(2000, {}, graded).mesh;
  check_mesh(refined);
  EXPECT_NEAR(static_cast<double>(refined.num_nodes()), 2000.0, 0.05 * 2000);
  EXPECT_NEAR(total_volume(refined), total_volume(uniform), 0.01 * total_volume(uniform));
  // A quarter of the size at the walls, against elements grown elsewhere to keep the node count.
  EXPECT_LT(mean_edge_at_the_slit(refined), 0.5 * mean_edge_at_the_slit(uniform));
  graded.slit_refinement = 0;
  EXPECT_THROW(generate_brain_mesh(2000, {}, graded), InputError);
}

TEST(BrainMesh, RelativeSizesAreFollowedAtTheSameNodeCount) {
  // A third of the size within 20 mm of the opening's centre (0, 0, 40 mm), twice elsewhere.
  const RelativeSizes sizes{.at = [](const Vec3& x) { return (x - Vec3(0, 0, 40 * mm)).norm() < 20 * mm ? 1.0 / 3 : 2.0; },
                            .smallest = 1.0 / 3,
                            .largest = 2.0};
  const TetMesh uniform = generate_brain_mesh(2000).mesh, sized = generate_brain_mesh(2000, {}, {}, 0.03, sizes).mesh;
  check_mesh(sized);
  EXPECT_NEAR(static_cast<double>(sized.num_nodes()), 2000.0, 0.05 * 2000);
  // Coarser chords on the curved surface cut off more volume: 1.2% here.
  EXPECT_NEAR(total_volume(sized), total_volume(uniform), 0.025 * total_volume(uniform));
  // The walls lie in the fine ball: a sixth of the coarse size, against a mesh that keeps the
  // node count; at least 2.5x smaller than the uniform mesh's there.
  EXPECT_LT(mean_edge_at_the_slit(sized), mean_edge_at_the_slit(uniform) / 2.5);
  BrainShape graded;
  graded.slit_refinement = 0.5;
  EXPECT_THROW(generate_brain_mesh(2000, {}, graded, 0.03, sizes), InputError);
}

}  // namespace
}  // namespace roifem::mesh
