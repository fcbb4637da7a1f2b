// SPDX-License-Identifier: GPL-3.0-or-later
// The distributed engine against the serial one, under mpirun -n 2 (and -n 1): the same K, the same
// trapezoidal steps, the same condensation. Every rank runs every test on the replicated serial
// model; the distributed vectors are gathered to every rank before they are compared.
#include <gtest/gtest.h>

#include <random>

#include "common/errors.hpp"
#include "condensation/reduced_model.hpp"
#include "distributed/condensed_roi.hpp"
#include "distributed/distributed_trapezoid.hpp"
#include "distributed/petsc_ts.hpp"
#include "fem/element.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "model/modal_reference.hpp"
#include "roi/roi.hpp"

namespace roifem::distributed {
namespace {

MPI_Comm world() { return PETSC_COMM_WORLD; }

/// The shipped brain as in the paper (base held, the opening's walls pulled apart, ramp 0.5 s),
/// optionally with gravity too (a load on the static part as well), as `element`.
struct Brain {
  explicit Brain(fem::Element element = fem::Element::tet4, bool gravity = false)
      : mesh(fem::element_mesh(mesh::read_mesh(std::string(ROIFEM_MESH_DIR) + "/brain-800.msh"), element)) {
    std::vector<model::SetLoad> loads{{"opening_left", Vec3(-0.016, 0, 0), model::Ramp{0.5}, {}},
                                      {"opening_right", Vec3(0.016, 0, 0), model::Ramp{0.5}, {}}};
    if (gravity) loads.push_back({"", Vec3::Zero(), model::Ramp{1.0}, Vec3(0, -9.81, 0)});
    const fem::MaterialMap materials(fem::material_preset("paper"));
    serial = model::build_fem_model(mesh, materials, {"base"}, loads, {}, element);
    frame = model::build_fem_model_without_stiffness(mesh, materials, {"base"}, loads, element);
  }
  mesh::TetMesh mesh;
  model::FemModel serial, frame;
};

/// PETSc options under a prefix: {"ksp_type", "cg"} sets -PREFIXksp_type cg.
void set_options(const std::string& prefix, std::initializer_list<std::pair<const char*, const char*>> options) {
  for (const auto& [key, value] : options)
    ASSERT_EQ(PetscOptionsSetValue(nullptr, ("-" + prefix + key).c_str(), value), 0) << key;
}

double relative_gap(const Vector& a, const Vector& b) { return (a - b).lpNorm<Eigen::Infinity>() / b.lpNorm<Eigen::Infinity>(); }

TEST(DistributedModel, NumbersEveryFreeNodeOnceInContiguousRanges) {
  const Brain brain;
  const DistributedModel m = distribute_model(brain.frame, world());
  std::vector<int> seen(static_cast<std::size_t>(m.nodes.count()), 0);
  for (int n = 0; n < brain.mesh.num_nodes(); ++n) {
    const PetscInt k = m.nodes.number[static_cast<std::size_t>(n)];
    EXPECT_EQ(k < 0, brain.frame.dofs->free_dof(n, 0) < 0) << "node " << n;
    if (k >= 0) ++seen[static_cast<std::size_t>(k)];
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
  EXPECT_EQ(3 * m.nodes.count(), brain.frame.dofs->num_free());
  int size = 1;
  MPI_Comm_size(world(), &size);
  for (int r = 0; r < size; ++r)
    EXPECT_GT(m.nodes.first[static_cast<std::size_t>(r) + 1], m.nodes.first[static_cast<std::size_t>(r)]);
  for (std::size_t i = 0; i < m.nodes.owned_nodes.size(); ++i)
    EXPECT_EQ(m.nodes.number[static_cast<std::size_t>(m.nodes.owned_nodes[i])], m.nodes.owned_begin() + static_cast<PetscInt>(i));
}

/// K x, M and the load patterns against the serial assembly's (a second assembly: column by column
/// from 3x3 blocks, where the distributed one adds whole element matrices through PETSc).
void expect_the_serial_operators(fem::Element element) {
  const Brain brain(element, true);
  const DistributedModel m = distribute_model(brain.frame, world());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Vector x(brain.serial.system.size());
  for (Index i = 0; i < x.size(); ++i) x(i) = uniform(random);
  const OwnedVec xd = m.distribute(x);
  OwnedVec yd = m.new_vector();
  ASSERT_EQ(MatMult(m.K.get(), xd.get(), yd.get()), 0);
  EXPECT_LT(relative_gap(m.gather(yd.get(), true), brain.serial.system.K * x), 1e-13);
  EXPECT_EQ(m.gather(m.mass.get(), true), Vector(brain.serial.system.M.diagonal()));
  ASSERT_EQ(m.loads.size(), 3U);
  for (std::size_t k = 0; k < m.loads.size(); ++k)
    EXPECT_EQ(m.gather(m.loads[k].pattern.get(), true), brain.serial.system.load.terms()[k].pattern);
  PetscBool symmetric = PETSC_FALSE;
  ASSERT_EQ(MatIsSymmetric(m.K.get(), 1e-12, &symmetric), 0);
  EXPECT_TRUE(symmetric);
}

TEST(DistributedModel, AssemblesTheSerialOperatorsTet4) { expect_the_serial_operators(fem::Element::tet4); }
TEST(DistributedModel, AssemblesTheSerialOperatorsTet10) { expect_the_serial_operators(fem::Element::tet10); }

TEST(DistributedModel, RefusesTheNodalPressureElementByName) {
  const Brain brain;
  model::FemModel frame = model::build_fem_model_without_stiffness(brain.mesh, fem::MaterialMap(fem::material_preset("paper")),
                                                                   {"base"}, {}, fem::Element::nodal_pressure);
  try {
    (void)distribute_model(frame, world());
    FAIL() << "nodal-pressure was distributed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nodal-pressure"), std::string::npos) << e.what();
  }
}

/// The largest gap between the distributed and the serial trapezoid over `steps` steps, relative to
/// the largest serial displacement; the distributed solver from options under `prefix`.
double trapezoid_gap(const Brain& brain, const std::string& prefix, long steps, double* iterations_per_step = nullptr) {
  const double dt = 0.05;
  const DistributedModel m = distribute_model(brain.frame, world());
  DistributedTrapezoid distributed(m, dt, 0.0, prefix);
  integrators::Trapezoid serial(dt);
  auto state = model::State::at_rest(brain.serial.system.size());
  serial.reset(brain.serial.system, state);
  double gap = 0, scale = 0;
  for (long k = 0; k < steps; ++k) {
    distributed.step();
    serial.step(state);
    EXPECT_DOUBLE_EQ(distributed.t(), state.t);
    gap = std::max(gap, (m.gather(distributed.u(), true) - state.u).lpNorm<Eigen::Infinity>());
    scale = std::max(scale, state.u.lpNorm<Eigen::Infinity>());
  }
  const double strain = 0.5 * state.u.dot(brain.serial.system.K * state.u);
  EXPECT_NEAR(distributed.strain_energy(), strain, 1e-7 * strain);
  if (iterations_per_step)
    *iterations_per_step = static_cast<double>(distributed.total_iterations()) / static_cast<double>(steps);
  return gap / scale;
}

TEST(DistributedTrapezoid, MumpsCholeskyMatchesTheSerialTrapezoidOverThePapers200Steps) {
  const Brain brain;
  EXPECT_LT(trapezoid_gap(brain, "", 200), 1e-10);
}

TEST(DistributedTrapezoid, GamgPreconditionedCgMatchesTheSerialTrapezoidTo1e8) {
  set_options("gamg_", {{"ksp_type", "cg"}, {"pc_type", "gamg"}, {"ksp_rtol", "1e-10"}});
  const Brain brain;
  double iterations = 0;
  EXPECT_LT(trapezoid_gap(brain, "gamg_", 200, &iterations), 1e-8);
  EXPECT_GT(iterations, 1.0);  // an iterative solve, not a factorization
  RecordProperty("iterations_per_step", std::to_string(iterations));
}

TEST(DistributedTrapezoid, BoomerAmgPreconditionedCgMatchesTheSerialTrapezoidTo1e8) {
  set_options("boomer_", {{"ksp_type", "cg"}, {"pc_type", "hypre"}, {"pc_hypre_type", "boomeramg"}, {"ksp_rtol", "1e-10"}});
  const Brain brain;
  EXPECT_LT(trapezoid_gap(brain, "boomer_", 50), 1e-8);
}

TEST(DistributedTrapezoid, TenNodeTetrahedraMatchTheSerialTrapezoid) {
  const Brain brain(fem::Element::tet10);
  EXPECT_LT(trapezoid_gap(brain, "", 40), 1e-10);
}

TEST(DistributedTrapezoid, NamesTheStepWhereTheSolverFails) {
  set_options("fail_", {{"ksp_type", "cg"}, {"pc_type", "none"}, {"ksp_max_it", "2"}});
  const Brain brain;
  const DistributedModel m = distribute_model(brain.frame, world());
  DistributedTrapezoid trapezoid(m, 0.05, 0.0, "fail_");
  try {
    trapezoid.step();
    FAIL() << "two CG iterations converged";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("step 1, t = 0.05 s"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("DIVERGED_ITS"), std::string::npos) << e.what();
  }
}

/// MUMPS's Schur complement and reduced loads against the serial static condensation (CHOLMOD on
/// one process), with gravity so that the static part is loaded too.
TEST(MumpsCondensation, EqualsTheSerialCondensationTo1e10) {
  const Brain brain(fem::Element::tet4, true);
  const roi::RoiSpec spec{.kind = roi::RoiSpec::Kind::nearest, .center = Vec3(0, 0, 0.040), .count = 306, .set = {}};
  const std::vector<int> roi_nodes = roi::select_roi_nodes(brain.mesh, *brain.serial.dofs, spec);
  const roi::Partition partition = roi::partition_dofs(brain.serial.system.K, *brain.serial.dofs, roi_nodes);
  const condensation::ReducedModel reference(brain.serial.system, partition, *brain.serial.dofs, condensation::Reduction{});
  const std::vector<Index> d = roi_free_dofs(*brain.frame.dofs, roi_nodes);
  ASSERT_EQ(d, partition.d);
  const DistributedModel m = distribute_model(brain.frame, world());
  const DistributedCondensation condensed = condense_with_mumps(m, d);
  int rank = 0;
  MPI_Comm_rank(world(), &rank);
  if (rank != 0) return;
  const DenseMatrix K_ref(reference.system().K);
  EXPECT_LT((condensed.K_tilde - K_ref).lpNorm<Eigen::Infinity>() / K_ref.lpNorm<Eigen::Infinity>(), 1e-10);
  ASSERT_EQ(condensed.f_tilde.size(), 3U);
  const Vector gravity_on_roi = roi::gather(brain.serial.system.load.terms()[2].pattern, d);
  const Vector& gravity_ref = reference.system().load.terms()[2].pattern;
  EXPECT_GT(relative_gap(gravity_on_roi, gravity_ref), 1e-3);  // the static part's load reaches the ROI
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_LT(relative_gap(condensed.f_tilde[k], reference.system().load.terms()[k].pattern), 1e-10) << "pattern " << k;
  // And the condensed model runs as the serial one does.
  const model::SecondOrderSystem roi = condensed_roi_system(m, condensed, d);
  integrators::Trapezoid a(0.05), b(0.05);
  auto sa = model::State::at_rest(roi.size()), sb = sa;
  a.reset(roi, sa);
  b.reset(reference.system(), sb);
  for (int k = 0; k < 40; ++k) {
    a.step(sa);
    b.step(sb);
  }
  EXPECT_LT(relative_gap(sa.u, sb.u), 1e-9);
}

TEST(MumpsCondensation, NamesAnEmptyRoi) {
  const Brain brain;
  const DistributedModel m = distribute_model(brain.frame, world());
  EXPECT_THROW((void)condense_with_mumps(m, {}), ModelError);
}

/// PETSc's TS integrators (one rank's, on every rank alike).
TEST(PetscTs, ThetaOneHalfIsTheTrapezoidalRule) {
  // Crank-Nicolson on y = [u; v] and Newmark's average acceleration are the same recurrence on a
  // linear system (from the same consistent start): two implementations, one answer.
  const Brain brain;
  const model::SecondOrderSystem& system = brain.serial.system;
  PetscTs theta(PetscTs::Method::theta, 0.05);
  integrators::Trapezoid trapezoid(0.05);
  auto a = model::State::at_rest(system.size()), b = a;
  theta.reset(system, a);
  trapezoid.reset(system, b);
  double gap = 0, scale = 0;
  for (int k = 1; k <= 40; ++k) {
    theta.advance_to(0.05 * k, a);
    trapezoid.advance_to(0.05 * k, b);
    EXPECT_DOUBLE_EQ(a.t, b.t);
    gap = std::max(gap, (a.u - b.u).lpNorm<Eigen::Infinity>());
    scale = std::max(scale, b.u.lpNorm<Eigen::Infinity>());
  }
  EXPECT_LT(gap / scale, 1e-9);
  EXPECT_EQ(theta.stats().steps, 40);
  EXPECT_EQ(theta.stats().lin_setups, 1);  // a fixed step: one factorization
}

/// The largest error of petsc-alpha2 at step dt against the exact modal solution of a damped beam
/// (60 x 20 x 20 mm, held at one end, its far end pulled in z with a ramp of 0.2 s) over 0.4 s.
double alpha2_error(double dt) {
  const mesh::TetMesh beam = mesh::structured_box_mesh(6, 2, 2, 0.06, 0.02, 0.02);
  const model::FemModel m = model::build_fem_model(beam, fem::Material::from_young_poisson(3000, 0.45, 1000, 0.8), {"x0"},
                                                   {{"x1", Vec3(0, 0, 1e-3), model::Ramp{0.2}, {}}});
  const model::ModalReference exact(m.system, model::State::at_rest(m.system.size()));
  PetscTs alpha2(PetscTs::Method::alpha2, dt);
  auto state = model::State::at_rest(m.system.size());
  alpha2.reset(m.system, state);
  double error = 0;
  for (long k = 1; k <= std::lround(0.4 / dt); ++k) {
    alpha2.advance_to(static_cast<double>(k) * dt, state);
    error = std::max(error, (state.u - exact.displacement(state.t)).lpNorm<Eigen::Infinity>());
  }
  return error;
}

TEST(PetscTs, Alpha2ConvergesAtSecondOrderToTheExactModalSolution) {
  const double coarse = alpha2_error(0.001), fine = alpha2_error(0.0005);
  const double order = std::log2(coarse / fine);
  EXPECT_GT(order, 1.8) << coarse << " " << fine;
  EXPECT_LT(order, 2.3) << coarse << " " << fine;
}

TEST(PetscTs, RowsMakeTheirIntegratorsWithAFixedStepOnly) {
  for (const integrators::IntegratorInfo& row : petsc_ts_rows()) {
    EXPECT_EQ(row.make(row, {.dt = 0.01})->name(), row.name);
    EXPECT_TRUE(row.fixed_step && !row.adaptive) << row.name;
    EXPECT_EQ(row.family, integrators::Family::petsc);
  }
}

}  // namespace
}  // namespace roifem::distributed

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const roifem::distributed::PetscSession session(argc, argv);
  if (session.rank() != 0) {  // one report: rank 0's (a failure on another rank still fails the run)
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
