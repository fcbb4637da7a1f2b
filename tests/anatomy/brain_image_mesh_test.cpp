// SPDX-License-Identifier: GPL-3.0-or-later
// Brains from images, end to end: a synthetic ball (whose volume and surface are known) and the
// Colin27 brain of mricron-data (scripts/setup.sh installs it): a connected mesh with a closed
// manifold boundary, positive tetrahedra above a quality floor, the voxels' volume, the node
// count asked for, and named sets that hold what their names say.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <numeric>
#include <regex>
#include <set>

#include "anatomy/brain_image_mesh.hpp"
#include "anatomy/image_volume.hpp"
#include "anatomy/nifti_fixture.hpp"
#include "common/errors.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"
#include "test_support.hpp"

namespace roifem::anatomy {
namespace {

template <class F>
std::string meshing_error_of(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}

/// The boundary's topology: V - E + F of its triangles (2 for a sphere), and whether every edge
/// lies on exactly two triangles and every vertex's triangles form a single fan (a manifold).
struct BoundaryTopology {
  long euler = 0;
  bool edge_manifold = true, vertex_manifold = true;
};

BoundaryTopology boundary_topology(const mesh::TetMesh& m) {
  const auto faces = mesh::boundary_faces(m);
  std::map<std::pair<int, int>, int> edges;
  std::map<int, std::vector<std::pair<int, int>>> fans;  // vertex -> the opposite edges of its triangles
  std::set<int> vertices;
  for (const auto& f : faces)
    for (int a = 0; a < 3; ++a) {
      const int p = f[static_cast<std::size_t>(a)], q = f[static_cast<std::size_t>((a + 1) % 3)],
                r = f[static_cast<std::size_t>((a + 2) % 3)];
      ++edges[{std::min(p, q), std::max(p, q)}];
      fans[p].emplace_back(q, r);
      vertices.insert(p);
    }
  BoundaryTopology t;
  for (const auto& [edge, count] : edges) t.edge_manifold = t.edge_manifold && count == 2;
  for (const auto& [vertex, fan] : fans) {  // walk the fan: q -> r links must form one cycle
    std::map<int, int> next;
    for (const auto& [q, r] : fan) next[q] = r;
    int at = fan.front().first, steps = 0;
    do {
      auto it = next.find(at);
      if (it == next.end()) break;
      at = it->second;
      ++steps;
    } while (at != fan.front().first && steps <= static_cast<int>(fan.size()));
    t.vertex_manifold = t.vertex_manifold && at == fan.front().first && steps == static_cast<int>(fan.size());
  }
  t.euler = static_cast<long>(vertices.size()) - static_cast<long>(edges.size()) + static_cast<long>(faces.size());
  return t;
}

int connected_pieces(const mesh::TetMesh& m) {
  std::vector<int> parent(static_cast<std::size_t>(m.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x)
      x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  for (const auto& t : m.tets)
    for (int a = 1; a < 4; ++a) parent[static_cast<std::size_t>(find(t[static_cast<std::size_t>(a)]))] = find(t[0]);
  std::set<int> roots;
  for (int n = 0; n < m.num_nodes(); ++n) roots.insert(find(n));
  return static_cast<int>(roots.size());
}

class BallImage : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    // A ball of radius 25 mm around the origin, 1 mm voxels, intensity 100.
    test::write_nifti(*dir_ / "ball.nii", {70, 70, 70}, 1.0, {-35, -35, -35}, [](int i, int j, int k) {
      const double x = i - 35.0, y = j - 35.0, z = k - 35.0;
      return x * x + y * y + z * z <= 25.0 * 25.0 ? 100.0f : 0.0f;
    });
  }
  static void TearDownTestSuite() { delete dir_; }
  static BrainImageOptions options() {
    BrainImageOptions o;
    o.image = *dir_ / "ball.nii";
    o.target_nodes = 1000;
    o.cut_height_mm = 0;
    return o;
  }
  static test::TempDir* dir_;
};
test::TempDir* BallImage::dir_ = nullptr;

TEST_F(BallImage, MeshesTheBallWithItsVolumeAndASphericalBoundary) {
  const BrainImageMesh result = mesh_brain_image(options(), *dir_ / "ball.msh");
  const mesh::TetMesh& m = result.mesh;
  EXPECT_NEAR(static_cast<double>(m.num_nodes()) / 1000, 1.0, 0.05);
  mesh::check_mesh(m);
  const double exact = 4.0 / 3.0 * 3.141592653589793 * 25 * 25 * 25;
  EXPECT_NEAR(mesh::total_volume(m) * 1e9 / exact, 1.0, 0.02);
  for (int n : m.set("surface").nodes) EXPECT_NEAR(m.node(n).norm() / mm, 25.0, 1.0) << "surface node " << n;
  const BoundaryTopology topology = boundary_topology(m);
  EXPECT_TRUE(topology.edge_manifold);
  EXPECT_TRUE(topology.vertex_manifold);
  EXPECT_EQ(topology.euler, 2);
  EXPECT_EQ(connected_pieces(m), 1);
  EXPECT_EQ(m.sets.count("grey_matter"), 0u) << "a binary image has no tissue classes";
}

TEST_F(BallImage, AnIncisionRefinesWhereAnOpeningWouldBeCarvedAndCarvesNothing) {
  // A box over the top, 20 mm long and 10 mm deep, as an opening (6 mm wide) and as an incision
  // (2 mm): the opening takes its voxels out of the mask and names its walls; the incision keeps
  // the whole ball, names none, and meshes its box finer than the box's mirror image under the ball
  // (elements of the width there, about 4.6 mm elsewhere).
  BrainImageOptions opening = options(), incision = options();
  opening.opening = SurgicalOpening{.centre_x_mm = 0, .centre_y_mm = 0, .width_mm = 6, .length_mm = 20, .depth_mm = 10};
  incision.opening = SurgicalOpening{.centre_x_mm = 0, .centre_y_mm = 0, .width_mm = 2, .length_mm = 20, .depth_mm = 10};
  incision.opening->carved = false;
  const BrainImageMesh carved = mesh_brain_image(opening), whole = mesh_brain_image(incision);
  double ball_mm3 = 0;  // the mask's voxels (1 mm^3 each), counted here
  for (int i = 0; i < 70; ++i)
    for (int j = 0; j < 70; ++j)
      for (int k = 0; k < 70; ++k) {
        const double x = i - 35.0, y = j - 35.0, z = k - 35.0;
        ball_mm3 += x * x + y * y + z * z <= 25.0 * 25.0 ? 1 : 0;
      }
  EXPECT_DOUBLE_EQ(whole.mask_volume_mm3, ball_mm3);
  EXPECT_LT(carved.mask_volume_mm3, ball_mm3 - 6 * 20 * 5);  // at least half the box's depth carved
  for (const char* name : {"opening_left", "opening_right", "opening_floor"}) {
    EXPECT_EQ(carved.mesh.sets.count(name), 1u) << name;
    EXPECT_EQ(whole.mesh.sets.count(name), 0u) << name;
  }
  ASSERT_TRUE(whole.opening_centre_mm.has_value());
  EXPECT_NEAR(whole.opening_centre_mm->z(), 20.0, 1.0);  // the ball's top (25 mm) less half the depth
  // Nodes in the box against its mirror image through z = 0 (as far inside the ball, no refinement).
  long in_box = 0, in_mirror = 0;
  for (Index n = 0; n < whole.mesh.num_nodes(); ++n) {
    const Vec3 x = whole.mesh.node(n) / mm;
    if (std::abs(x.x()) > 3 || std::abs(x.y()) > 10) continue;
    in_box += x.z() >= 15 ? 1 : 0;
    in_mirror += x.z() <= -15 ? 1 : 0;
  }
  EXPECT_GT(in_box, 2 * in_mirror);
  std::cout << "incision: " << in_box << " nodes in its box, " << in_mirror << " in the mirror image; the mask "
            << whole.mask_volume_mm3 << " mm^3 (the opening's " << carved.mask_volume_mm3 << ")\n";
}

TEST_F(BallImage, NamesARegionOutsideTheBrainAndLeavesNoFile) {
  BrainImageOptions o = options();
  o.regions.push_back(parse_region("far=sphere:0,0,60,5"));
  const auto out = *dir_ / "far.msh";
  const std::string message = meshing_error_of([&] { mesh_brain_image(o, out); });
  EXPECT_TRUE(std::regex_search(message, std::regex("--region far=sphere:0,0,60,5: no boundary triangle lies within 5 mm of the "
                                                    "point; the brain's surface is 3[45].[0-9] mm from it")))
      << message;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST_F(BallImage, RefusesBadRegionsAndAnEmptyImage) {
  EXPECT_NE(meshing_error_of([] { parse_region("x=cube:1,2,3"); }).find("unknown kind 'cube'"), std::string::npos);
  EXPECT_NE(meshing_error_of([] { parse_region("x=sphere:1,2,3"); }).find("expected NAME=sphere:X,Y,Z,RADIUS"),
            std::string::npos);
  EXPECT_NE(meshing_error_of([] { parse_region("x=sphere:1,2,3,-4"); }).find("the radius must be positive"), std::string::npos);
  BrainImageOptions o = options();
  o.regions.push_back(parse_region("motor=label:Precentral_R"));
  EXPECT_NE(meshing_error_of([&] { mesh_brain_image(o); }).find("a label region needs --atlas"), std::string::npos);
  test::write_nifti(*dir_ / "dark.nii", {8, 8, 8}, 1.0, {0, 0, 0}, [](int, int, int) { return 0.0f; });
  o = options();
  o.image = *dir_ / "dark.nii";
  EXPECT_NE(meshing_error_of([&] { mesh_brain_image(o); }).find("dark.nii: no voxel is above the mask threshold"),
            std::string::npos);
}

TEST_F(BallImage, RefusesAMaskTooSmallForTheNodesBeforeMeshing) {
  // Each used to loop for ever inside CGAL's make_mesh_3 (Random_points_on_sphere_3).
  test::write_nifti(*dir_ / "speck.nii", {9, 9, 9}, 1.0, {0, 0, 0},
                    [](int i, int j, int k) { return i == 4 && j == 4 && k == 4 ? 100.0f : 0.0f; });
  BrainImageOptions o = options();
  o.image = *dir_ / "speck.nii";
  o.target_nodes = 200;
  const auto out = *dir_ / "speck.msh";
  std::string message = meshing_error_of([&] { mesh_brain_image(o, out); });
  EXPECT_TRUE(
      std::regex_search(message, std::regex("speck.nii: the mask holds 1 mm\\^3 \\(1 voxels of 1 mm\\^3\\), and --nodes 200 "
                                            "needs at least 1067 mm\\^3 \\(elements of two voxels, 2 mm, or larger\\)")))
      << message;
  EXPECT_FALSE(std::filesystem::exists(out));
  o = options();
  o.cut_height_mm = 60;  // the ball is 50 mm high
  message = meshing_error_of([&] { mesh_brain_image(o, out); });
  EXPECT_TRUE(
      std::regex_search(message, std::regex("ball.nii: the mask holds 0 mm\\^3 .* after the bottom cut \\(--cut-mm 60\\), "
                                            "and --nodes 1000 needs .*a smaller --cut-mm")))
      << message;
  EXPECT_FALSE(std::filesystem::exists(out));
}

/// The Colin27 brain at about 2,000 nodes, meshed once for the suite (a ctest entry of its own).
class Colin27Brain : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_FALSE(colin27_image().empty()) << "mricron-data is not installed (scripts/setup.sh installs it)";
    dir_ = new test::TempDir;
    BrainImageOptions o;
    o.image = colin27_image();
    o.atlas = colin27_atlas();
    o.target_nodes = 2000;
    o.regions = {parse_region("motor=label:Precentral_R"), parse_region("vertex=sphere:0,-20,80,20")};
    result_ = new BrainImageMesh(mesh_brain_image(o, *dir_ / "colin27.msh"));
  }
  static void TearDownTestSuite() {
    delete result_;
    delete dir_;
  }
  static test::TempDir* dir_;
  static BrainImageMesh* result_;
};
test::TempDir* Colin27Brain::dir_ = nullptr;
BrainImageMesh* Colin27Brain::result_ = nullptr;

TEST_F(Colin27Brain, IsOneValidPieceWithAClosedManifoldBoundary) {
  const mesh::TetMesh& m = result_->mesh;
  EXPECT_NEAR(static_cast<double>(m.num_nodes()) / 2000, 1.0, 0.05);
  mesh::check_mesh(m);  // every tetrahedron positively oriented
  EXPECT_GE(mesh::mesh_statistics(m).quality_min, 0.1);
  EXPECT_EQ(connected_pieces(m), 1);
  const BoundaryTopology topology = boundary_topology(m);
  EXPECT_TRUE(topology.edge_manifold);
  EXPECT_TRUE(topology.vertex_manifold);
  // Its genus is not asserted: smoothing may bridge a narrow gap (the 2,000-node surface has
  // one handle, Euler characteristic 0); a handle changes nothing for the elements.
  EXPECT_LE(topology.euler, 2);
}

TEST_F(Colin27Brain, HoldsTheVolumeOfTheTissueVoxels) {
  // Independently of the mask cleaning: the template's non-zero voxels above the cut plane (the
  // holes the cleaning fills hold 0.18% of the brain, the specks it drops one voxel).
  const ImageVolume image = read_nifti(colin27_image());
  double lowest = 1e300, volume = 0;
  for (int k = 0; k < image.dims[2]; ++k)
    for (int j = 0; j < image.dims[1]; ++j)
      for (int i = 0; i < image.dims[0]; ++i)
        if (image.at(i, j, k) > 0) lowest = std::min(lowest, image.to_mm(Eigen::Vector3d(i, j, k)).z());
  EXPECT_NEAR(result_->cut_plane_z_mm, lowest + 5, 1e-9);
  for (int k = 0; k < image.dims[2]; ++k)
    for (int j = 0; j < image.dims[1]; ++j)
      for (int i = 0; i < image.dims[0]; ++i)
        if (image.at(i, j, k) > 0 && image.to_mm(Eigen::Vector3d(i, j, k)).z() >= lowest + 5) volume += image.voxel_volume_mm3();
  EXPECT_NEAR(mesh::total_volume(result_->mesh) * 1e9 / volume, 1.0, 0.02);
}

TEST_F(Colin27Brain, NamesItsSetsByWhatTheyHold) {
  const mesh::TetMesh& m = result_->mesh;
  // The tissues partition the brain; white matter is the brighter in T1.
  const ImageVolume image = read_nifti(colin27_image());
  double sum[2] = {0, 0};
  const char* tissues[2] = {"grey_matter", "white_matter"};
  std::size_t count = m.set("csf").tets.size();
  for (int t = 0; t < 2; ++t) {
    for (int e : m.set(tissues[t]).tets) {
      Vec3 centre = Vec3::Zero();
      for (int n : m.tets[static_cast<std::size_t>(e)]) centre += m.node(n) / mm / 4;
      sum[t] += image.nearest(centre);
    }
    count += m.set(tissues[t]).tets.size();
  }
  EXPECT_EQ(count, m.tets.size());
  EXPECT_GT(sum[1] / static_cast<double>(m.set("white_matter").tets.size()),
            sum[0] / static_cast<double>(m.set("grey_matter").tets.size()) + 10);
  // The brainstem cut: flat, facing down, at the cut plane.
  const auto& cut = m.set("brainstem_cut");
  ASSERT_FALSE(cut.triangles.empty());
  for (const auto& t : cut.triangles)
    for (int n : t) EXPECT_NEAR(m.node(n).z() / mm, result_->cut_plane_z_mm, 3.0);
  // The sphere region lies within its radius; the label region over the right precentral gyrus
  // (AAL label 2): right hemisphere (x > 0), between the frontal and parietal lobes.
  for (int n : m.set("vertex").nodes) EXPECT_LT((m.node(n) / mm - Vec3(0, -20, 80)).norm(), 20 + 15);
  const auto& motor = m.set("motor");
  ASSERT_GT(motor.triangles.size(), 10u);
  Vec3 centre = Vec3::Zero();
  for (int n : motor.nodes) centre += m.node(n) / mm / static_cast<double>(motor.nodes.size());
  EXPECT_GT(centre.x(), 15);
  EXPECT_GT(centre.y(), -40);
  EXPECT_LT(centre.y(), 10);
}

TEST_F(Colin27Brain, ReadsBackFromItsFile) {
  const mesh::TetMesh read = mesh::read_mesh(*dir_ / "colin27.msh");
  EXPECT_EQ(read.num_nodes(), result_->mesh.num_nodes());
  EXPECT_LT((read.nodes - result_->mesh.nodes).cwiseAbs().maxCoeff(), 1e-12);
  // The file groups tetrahedra by the sets they belong to: the same tetrahedra, in another order.
  EXPECT_EQ(std::multiset<mesh::Tet>(read.tets.begin(), read.tets.end()),
            std::multiset<mesh::Tet>(result_->mesh.tets.begin(), result_->mesh.tets.end()));
  for (const auto& [name, set] : result_->mesh.sets) {
    EXPECT_EQ(read.set(name).nodes, set.nodes) << name;
    EXPECT_EQ(read.set(name).tets.size(), set.tets.size()) << name;
    EXPECT_EQ(read.set(name).triangles.size(), set.triangles.size()) << name;
  }
}

}  // namespace
}  // namespace roifem::anatomy
