// SPDX-License-Identifier: GPL-3.0-or-later
#include "distributed/distributed_model.hpp"

#include "common/errors.hpp"
#include "fem/element.hpp"
#include "fem/tet10.hpp"
#include "fem/tet4.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"

namespace roifem::distributed {

namespace {

/// Per owned node: how many neighbouring free nodes (itself included) it owns and how many others do.
void count_couplings(const NodePartition& p, const NodeGraph& graph, std::vector<PetscInt>& own, std::vector<PetscInt>& other) {
  own.assign(p.owned_nodes.size(), 1);
  other.assign(p.owned_nodes.size(), 0);
  for (std::size_t i = 0; i < p.owned_nodes.size(); ++i) {
    const auto a = static_cast<std::size_t>(p.owned_nodes[i]);
    for (PetscInt j = graph.start[a]; j < graph.start[a + 1]; ++j) {
      const PetscInt k = p.number[static_cast<std::size_t>(graph.neighbours[static_cast<std::size_t>(j)])];
      if (k < 0) continue;
      (k >= p.owned_begin() && k < p.owned_end() ? own[i] : other[i]) += 1;
    }
  }
}

/// The element's matrix, row-major (symmetric, so either), nodes in element_nodes' order.
std::vector<PetscScalar> element_matrix(const mesh::TetMesh& mesh, const std::vector<int>& nodes, const fem::Material& m) {
  const Vec3 x0 = mesh.node(nodes[0]), x1 = mesh.node(nodes[1]), x2 = mesh.node(nodes[2]), x3 = mesh.node(nodes[3]);
  if (nodes.size() == 4) {
    const fem::ElementMatrix k = fem::tet4_stiffness(fem::tet4_geometry(x0, x1, x2, x3), m);
    return {k.data(), k.data() + k.size()};
  }
  const fem::Tet10Matrix k = fem::tet10_stiffness(fem::tet10_geometry(x0, x1, x2, x3), m);
  return {k.data(), k.data() + k.size()};
}

}  // namespace

void DistributedModel::load_at(double t, Vec f) const {
  check(VecSet(f, 0.0), "VecSet");
  for (const auto& load : loads) check(VecAXPY(f, load.ramp.value(t), load.pattern.get()), "VecAXPY");
}

OwnedVec DistributedModel::new_vector() const {
  OwnedVec v;
  check(MatCreateVecs(K.get(), v.out(), nullptr), "MatCreateVecs");
  return v;
}

PetscInt DistributedModel::index_of_free_dof(Index free) const {
  const Index full = frame->dofs->full_dof(free);
  return 3 * nodes.number[static_cast<std::size_t>(full / 3)] + static_cast<PetscInt>(full % 3);
}

OwnedVec DistributedModel::distribute(const Vector& serial) const {
  OwnedVec v = new_vector();
  PetscScalar* x = nullptr;
  check(VecGetArray(v.get(), &x), "VecGetArray");
  for (std::size_t i = 0; i < nodes.owned_nodes.size(); ++i)
    for (int c = 0; c < 3; ++c) x[3 * i + static_cast<std::size_t>(c)] = serial(frame->dofs->free_dof(nodes.owned_nodes[i], c));
  check(VecRestoreArray(v.get(), &x), "VecRestoreArray");
  return v;
}

Vector DistributedModel::gather(Vec x, bool to_all) const {
  OwnedScatter scatter;
  OwnedVec whole;
  check(to_all ? VecScatterCreateToAll(x, scatter.out(), whole.out()) : VecScatterCreateToZero(x, scatter.out(), whole.out()),
        "VecScatterCreateTo");
  check(VecScatterBegin(scatter.get(), x, whole.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(scatter.get(), x, whole.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  PetscInt n = 0;
  check(VecGetLocalSize(whole.get(), &n), "VecGetLocalSize");
  if (n == 0) return {};
  const PetscScalar* w = nullptr;
  check(VecGetArrayRead(whole.get(), &w), "VecGetArrayRead");
  Vector serial(frame->dofs->num_free());
  for (Index i = 0; i < serial.size(); ++i) serial(i) = w[index_of_free_dof(i)];
  check(VecRestoreArrayRead(whole.get(), &w), "VecRestoreArrayRead");
  return serial;
}

void check_distributable(const scenario::Scenario& sc) {
  scenario::refuse_run_only_tables(sc, "roifem-mpi");
  if (sc.tools.empty()) return;
  std::string names;
  for (const auto& tool : sc.tools) names += (names.empty() ? "'" : ", '") + tool.name + "'";
  throw InputError("roifem-mpi: scenario " + sc.file.string() + " has [[tool]]s (" + names +
                   "); the distributed model takes loads only and would leave them out: run it with `roifem run " +
                   sc.file.string() + " --out DIR`, which takes them");
}

std::unique_ptr<ScenarioFrame> scenario_frame(const scenario::Scenario& sc) {
  check_distributable(sc);
  auto f = std::make_unique<ScenarioFrame>();
  f->mesh = mesh::read_mesh(sc.mesh);
  mesh::check_mesh(f->mesh);
  f->mesh = fem::element_mesh(std::move(f->mesh), sc.element);
  f->model = model::build_fem_model_without_stiffness(f->mesh, fem::MaterialMap(f->mesh, sc.material, sc.material_regions),
                                                      sc.fixed_sets, sc.loads, sc.element);
  return f;
}

DistributedModel distribute_model(const model::FemModel& frame, MPI_Comm comm) {
  if (frame.element == fem::Element::nodal_pressure)
    throw InputError(
        "roifem-mpi: element = \"nodal-pressure\" is not distributed (its K couples nodes two elements apart); "
        "use \"tet4\" or \"tet10\"");
  if (frame.dofs->prescribed().squaredNorm() > 0)
    throw InputError("roifem-mpi: non-zero prescribed displacements are not distributed; fix nodes at zero");
  const mesh::TetMesh& mesh = *frame.mesh;
  DistributedModel m;
  m.frame = &frame;
  const NodeGraph graph = NodeGraph::of(mesh);
  m.nodes = partition_free_nodes(mesh, *frame.dofs, graph, comm);
  const PetscInt owned = 3 * (m.nodes.owned_end() - m.nodes.owned_begin());
  check(MatCreate(comm, m.K.out()), "MatCreate");
  check(MatSetSizes(m.K.get(), owned, owned, m.dofs(), m.dofs()), "MatSetSizes");
  check(MatSetType(m.K.get(), MATAIJ), "MatSetType");
  check(MatSetBlockSize(m.K.get(), 3), "MatSetBlockSize");
  std::vector<PetscInt> own, other;
  count_couplings(m.nodes, graph, own, other);
  check(MatXAIJSetPreallocation(m.K.get(), 3, own.data(), other.data(), nullptr, nullptr), "MatXAIJSetPreallocation");
  check(MatSetOption(m.K.get(), MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  // Each element once, by the owner of its first free node; PETSc ignores negative (fixed) indices.
  std::vector<PetscInt> blocks;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    const std::vector<int> nodes = element_nodes(mesh, e);
    blocks.resize(nodes.size());
    PetscInt first_free = -1;
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      blocks[a] = m.nodes.number[static_cast<std::size_t>(nodes[a])];
      if (first_free < 0) first_free = blocks[a];
    }
    if (first_free < 0 || m.nodes.owner(first_free) != m.nodes.rank) continue;
    const std::vector<PetscScalar> k = element_matrix(mesh, nodes, frame.materials.of(e));
    const auto n = static_cast<PetscInt>(nodes.size());
    check(MatSetValuesBlocked(m.K.get(), n, blocks.data(), n, blocks.data(), k.data(), ADD_VALUES), "MatSetValuesBlocked");
  }
  check(MatAssemblyBegin(m.K.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(m.K.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  m.mass = m.distribute(frame.system.M.diagonal());
  m.alpha = frame.system.damping.alpha;
  for (const auto& term : frame.system.load.terms()) m.loads.push_back({m.distribute(term.pattern), term.ramp});
  m.coordinates = m.new_vector();
  check(VecSetBlockSize(m.coordinates.get(), 3), "VecSetBlockSize");
  PetscScalar* x = nullptr;
  check(VecGetArray(m.coordinates.get(), &x), "VecGetArray");
  for (std::size_t i = 0; i < m.nodes.owned_nodes.size(); ++i)
    for (int c = 0; c < 3; ++c) x[3 * i + static_cast<std::size_t>(c)] = mesh.nodes(c, m.nodes.owned_nodes[i]);
  check(VecRestoreArray(m.coordinates.get(), &x), "VecRestoreArray");
  return m;
}

}  // namespace roifem::distributed
