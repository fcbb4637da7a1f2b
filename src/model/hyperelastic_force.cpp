// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/hyperelastic_force.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "solvers/sparse_positions.hpp"

namespace roifem::model {

namespace {

/// Whether a material's elements take a hyperelastic law (fem/material_model.hpp's table).
bool follows_the_law(const fem::Material& m) { return fem::material_model_info(m.model).hyperelastic; }

/// The same regions with the neo-Hookean ones at zero moduli: the linear elements' K alone.
fem::MaterialMap linear_part(const fem::MaterialMap& materials) {
  return materials.mapped([&](fem::Material m) {
    if (follows_the_law(m)) m.lambda = m.mu = 0;
    return m;
  });
}

/// "LAW, every element" or "LAW, n of N elements", the laws of `elements` named in the table's order.
std::string description_of(const fem::MaterialMap& materials, const std::vector<Index>& elements, Index all, const char* where) {
  std::string laws;
  for (const auto& row : fem::material_model_table()) {
    const bool taken = std::any_of(elements.begin(), elements.end(), [&](Index e) { return materials.of(e).model == row.model; });
    if (taken) laws += (laws.empty() ? "" : " and ") + std::string(row.name);
  }
  const auto nonlinear = static_cast<Index>(elements.size());
  return (laws.empty() ? std::string("hyperelastic") : laws) + ", " +
         (nonlinear == all ? std::string("every element")
                           : std::to_string(nonlinear) + " of " + std::to_string(all) + " elements") +
         where;
}

/// Whether tetrahedron e has a node (corner or midpoint) that `marked` marks.
bool element_touches(const mesh::TetMesh& mesh, Index e, const std::vector<bool>& marked) {
  bool touches = false;
  for (const int n : mesh.tets[static_cast<std::size_t>(e)]) touches |= marked[static_cast<std::size_t>(n)];
  if (mesh.is_quadratic())
    for (const int n : mesh.midside.of_tet[static_cast<std::size_t>(e)]) touches |= marked[static_cast<std::size_t>(n)];
  return touches;
}

}  // namespace

HyperelasticForce::HyperelasticForce(std::shared_ptr<const fem::DofMap> dofs, const mesh::TetMesh& mesh,
                                     const fem::MaterialMap& materials, fem::Element element, std::vector<Index> elements,
                                     const SparseMatrix& K_lin, bool K_lin_is_zero, std::string description,
                                     std::vector<Tool> tools)
    : dofs_(std::move(dofs)),
      assembler_(std::make_shared<const fem::HyperelasticAssembler>(mesh, *dofs_, materials, std::move(elements), element)),
      motion_(tools.empty() ? nullptr : make_motion(mesh, *dofs_, materials, element, assembler_->elements(), std::move(tools))),
      K_lin_(K_lin),
      K_lin_is_zero_(K_lin_is_zero),
      assembler_in_K_(solvers::positions_in(assembler_->pattern(), K_lin_)),
      element_tangent_(assembler_->pattern()),
      description_(std::move(description)) {}

std::shared_ptr<const HyperelasticForce::Motion> HyperelasticForce::make_motion(
    const mesh::TetMesh& mesh, const fem::DofMap& dofs, const fem::MaterialMap& materials, fem::Element element,
    const std::vector<Index>& elements, std::vector<Tool> tools) {
  auto motion = std::make_shared<Motion>();
  const auto T = static_cast<Index>(tools.size());
  // Each tool node's component: 3 a + c, or -1.
  std::vector<Index> tool_component(static_cast<std::size_t>(dofs.num_full()), -1);
  for (Index a = 0; a < T; ++a)
    for (const int n : tools[static_cast<std::size_t>(a)].nodes)
      for (int c = 0; c < 3; ++c) {
        if (dofs.free_dof(n, c) >= 0) throw Error("internal: a tool's node is free in the law's dofs");
        tool_component[3 * static_cast<std::size_t>(n) + static_cast<std::size_t>(c)] = 3 * a + c;
      }
  // The law's elements' stiffness at rest over the unknowns and the tools' dofs together: its
  // columns at the tools' dofs, summed per tool, are K_ug and K_gg.
  fem::Constraints with_tools(mesh.num_nodes());
  fem::Constraints at_tools(mesh.num_nodes());
  for (Index full = 0; full < dofs.num_full(); ++full) {
    const auto n = full / 3;
    const auto c = static_cast<int>(full % 3);
    if (tool_component[static_cast<std::size_t>(full)] >= 0) continue;
    at_tools.prescribe(n, c);
    if (dofs.free_dof(n, c) < 0) with_tools.prescribe(n, c, dofs.prescribed()[full]);
  }
  const fem::DofMap both(with_tools);
  SparseMatrix K_at_rest;
  Vector f(both.num_free());
  fem::HyperelasticAssembler(mesh, both, materials, elements, element)
      .force_and_tangent(both.expand(Vector::Zero(both.num_free())), f, K_at_rest);
  std::vector<Eigen::Triplet<double>> coupling;
  motion->K_gg = DenseMatrix::Zero(3 * T, 3 * T);
  for (Index j = 0; j < K_at_rest.outerSize(); ++j) {
    const Index to_tool = tool_component[static_cast<std::size_t>(both.full_dof(j))];
    if (to_tool < 0) continue;
    for (SparseMatrix::InnerIterator it(K_at_rest, j); it; ++it) {
      const Index row_full = both.full_dof(it.row());
      if (const Index from_tool = tool_component[static_cast<std::size_t>(row_full)]; from_tool >= 0)
        motion->K_gg(from_tool, to_tool) += it.value();
      else
        coupling.emplace_back(dofs.free_dof(row_full / 3, static_cast<int>(row_full % 3)), to_tool, it.value());
    }
  }
  motion->K_ug.resize(dofs.num_free(), 3 * T);
  motion->K_ug.setFromTriplets(coupling.begin(), coupling.end());
  // The law's elements at the tools' nodes, for the tools' forces.
  motion->tool_dofs = std::make_shared<const fem::DofMap>(at_tools);
  std::vector<bool> tool_node(static_cast<std::size_t>(mesh.num_nodes()), false);
  for (const Tool& tool : tools)
    for (const int n : tool.nodes) tool_node[static_cast<std::size_t>(n)] = true;
  std::vector<Index> touching;
  for (const Index e : elements)
    if (element_touches(mesh, e, tool_node)) touching.push_back(e);
  motion->at_tools =
      std::make_shared<const fem::HyperelasticAssembler>(mesh, *motion->tool_dofs, materials, std::move(touching), element);
  for (Index i = 0; i < motion->tool_dofs->num_free(); ++i)
    motion->component.push_back(tool_component[static_cast<std::size_t>(motion->tool_dofs->full_dof(i))]);
  motion->tools = std::move(tools);
  return motion;
}

Vector HyperelasticForce::Motion::positions(double t) const {
  Vector g(3 * static_cast<Index>(tools.size()));
  for (std::size_t a = 0; a < tools.size(); ++a) g.segment<3>(3 * static_cast<Index>(a)) = tools[a].path.at(t);
  return g;
}

const Vector& HyperelasticForce::displacement(const Vector& u, const Vector& g) const {
  // Only the free entries (and the tools' nodes) change between calls: the full vector is kept, its
  // prescribed entries written once (a hybrid ROI's free dofs are a few thousand of a brain's 3N).
  if (U_.size() != dofs_->num_full()) U_ = dofs_->prescribed();
  if (u.size() != dofs_->num_free()) throw Error("internal: the law's displacement does not match its dofs");
  for (Index i = 0; i < u.size(); ++i) U_[dofs_->full_dof(i)] = u[i];
  if (motion_)
    for (std::size_t a = 0; a < motion_->tools.size(); ++a)
      for (const int n : motion_->tools[a].nodes)
        U_.segment<3>(3 * n) = dofs_->prescribed().segment<3>(3 * n) + g.segment<3>(3 * static_cast<Index>(a));
  return U_;
}

void HyperelasticForce::force(double t, const Vector& u, Vector& f) const {
  const Vector g = positions(t);
  assembler_->force(displacement(u, g), f);
  add_linear(u, f);
  if (motion_) f.noalias() -= motion_->K_ug * g;
}

void HyperelasticForce::force_and_tangent(double t, const Vector& u, Vector& f, SparseMatrix& K_t) const {
  const Vector g = positions(t);
  assembler_->force_and_tangent(displacement(u, g), f, element_tangent_);
  add_linear(u, f);
  if (motion_) f.noalias() -= motion_->K_ug * g;
  add_elements_to_K_lin(1.0, K_t);
}

void HyperelasticForce::excess_force(const Vector& u, Vector& g) const {
  if (motion_)
    throw InputError("the law's excess over the linear model is not formed where tools move its elements (" + description_ + ")");
  assembler_->excess_force_free(u, g);
}

Vector HyperelasticForce::tool_force_correction(double t, const Vector& u) const {
  if (!motion_) return {};
  const Vector g = positions(t);
  Vector at_dofs(motion_->tool_dofs->num_free());
  motion_->at_tools->force(displacement(u, g), at_dofs);
  Vector F = -(motion_->K_ug.transpose() * u) - motion_->K_gg * g;
  for (Index i = 0; i < at_dofs.size(); ++i) F[motion_->component[static_cast<std::size_t>(i)]] += at_dofs[i];
  return F;
}

std::shared_ptr<const InternalForce> HyperelasticForce::with_ramp(const Ramp& ramp) const {
  auto ramped = std::make_shared<HyperelasticForce>(*this);
  if (motion_) {
    auto motion = std::make_shared<Motion>(*motion_);
    for (Tool& tool : motion->tools) {
      if (tool.path.trajectory) throw Error("tool '" + tool.name + "' follows a trajectory: its ramp cannot be replaced");
      tool.path.ramp = ramp;
    }
    ramped->motion_ = std::move(motion);
  }
  return ramped;
}

void HyperelasticForce::add_linear(const Vector& u, Vector& f) const {
  if (K_lin_is_zero_) return;
  if (!K_split_) {
    f.noalias() += K_lin_ * u;
    return;
  }
  // K_lin through its split form: the interface's dense block by a symmetric BLAS product, not as
  // tens of thousands of scattered sparse entries.
  linear_u_.resize(u.size());
  K_split_->apply(u, linear_u_);
  f += linear_u_;
}

void HyperelasticForce::add_elements_to_K_lin(double share_of_K_lin, SparseMatrix& K) const {
  // K = share K_lin + the elements' matrix, in K_lin's pattern, value by value (no allocation).
  if (K.nonZeros() != K_lin_.nonZeros() || K.rows() != K_lin_.rows()) K = K_lin_;
  double* t = K.valuePtr();
  const double* lin = K_lin_.valuePtr();
  for (Index i = 0; i < K_lin_.nonZeros(); ++i) t[i] = share_of_K_lin * lin[i];
  const double* e = element_tangent_.valuePtr();
  for (std::size_t i = 0; i < assembler_in_K_.size(); ++i) t[assembler_in_K_[i]] += e[i];
}

void HyperelasticForce::discrete_gradient(const Vector& u_a, const Vector& u_b, Vector& f_alg) const {
  if (motion_) throw Error("internal: a discrete gradient of a force that tools move");
  f_alg.resize(u_a.size());
  assembler_->discrete_gradient(dofs_->expand(u_a), dofs_->expand(u_b), f_alg);
  add_linear(0.5 * (u_a + u_b), f_alg);
}

void HyperelasticForce::discrete_gradient_and_tangent(const Vector& u_a, const Vector& u_b, Vector& f_alg,
                                                      SparseMatrix& K_alg) const {
  if (motion_) throw Error("internal: a discrete gradient of a force that tools move");
  f_alg.resize(u_a.size());
  assembler_->discrete_gradient_and_tangent(dofs_->expand(u_a), dofs_->expand(u_b), f_alg, element_tangent_);
  add_linear(0.5 * (u_a + u_b), f_alg);
  add_elements_to_K_lin(0.5, K_alg);
}

double HyperelasticForce::energy(double t, const Vector& u) const {
  const Vector g = positions(t);
  double W = assembler_->energy(displacement(u, g));
  if (!K_lin_is_zero_) {
    Vector K_lin_u = Vector::Zero(u.size());
    add_linear(u, K_lin_u);
    W += 0.5 * u.dot(K_lin_u);
  }
  if (motion_) W -= u.dot(motion_->K_ug * g) + 0.5 * g.dot(motion_->K_gg * g);
  return W;
}

namespace {

/// The law on `elements` over `dofs`, every other element by K: K_lin = K - the elements' linear
/// stiffness (their tangent at rest, which the law's linearization makes the linear one), in K's
/// pattern, so that the force's tangent at rest is K.
std::shared_ptr<const InternalForce> law_on(std::shared_ptr<const fem::DofMap> dofs, const mesh::TetMesh& mesh,
                                            const fem::MaterialMap& materials, std::vector<Index> elements, const SparseMatrix& K,
                                            const std::vector<Tool>& tools, const char* where,
                                            const SplitMatrix* K_split = nullptr) {
  const fem::Element element = mesh.is_quadratic() ? fem::Element::tet10 : fem::Element::tet4;
  SparseMatrix K_at_rest;
  Vector f(dofs->num_free());
  fem::HyperelasticAssembler(mesh, *dofs, materials, elements, element)
      .force_and_tangent(dofs->expand(Vector::Zero(dofs->num_free())), f, K_at_rest);
  SparseMatrix K_lin = K;
  K_lin.makeCompressed();
  const std::vector<int> at = solvers::positions_in(K_at_rest, K_lin);
  for (std::size_t i = 0; i < at.size(); ++i) K_lin.valuePtr()[at[i]] -= K_at_rest.valuePtr()[i];
  std::string description = description_of(materials, elements, mesh.num_tets(), where);
  auto law = std::make_shared<HyperelasticForce>(std::move(dofs), mesh, materials, element, std::move(elements), std::move(K_lin),
                                                 false, std::move(description), tools);
  if (K_split && !K_split->empty()) law->use_split_products(*K_split, K_at_rest);
  return law;
}

/// The hybrid ROI's law stops at the static part, where nodal averages would reach across it.
void refuse_nodal_pressure(fem::Element element) {
  if (element == fem::Element::nodal_pressure)
    throw InputError(
        "the hybrid ROI does not take the nodal-pressure element at finite strain (its nodes' averaged volume would reach "
        "into the linear condensed part): give element = \"tet4\" or \"tet10\", or run the full model");
}

/// The nodal-pressure element averages J over every element at a node: each must follow a law.
void require_every_element_hyperelastic(const mesh::TetMesh& mesh, const fem::MaterialMap& materials, fem::Element element) {
  if (element != fem::Element::nodal_pressure) return;
  for (Index e = 0; e < mesh.num_tets(); ++e)
    if (!follows_the_law(materials.of(e)))
      throw InputError(
          "the nodal-pressure element at finite strain takes a model whose every material follows a hyperelastic "
          "law: tetrahedron " +
          std::to_string(e) +
          " is linear (give its region model = \"neo-hookean\" or \"ogden\", or element = "
          "\"tet4\" or \"tet10\")");
}

/// The hybrid's nonlinear elements: neo-Hookean, with no node in the static part, and some node
/// that moves (an ROI node or a tool's): one of held nodes alone never strains.
std::vector<Index> hybrid_elements(const mesh::TetMesh& mesh, const fem::DofMap& dofs, const fem::MaterialMap& materials,
                                   const roi::Partition& partition, const std::vector<Tool>& tools) {
  std::vector<bool> static_node(static_cast<std::size_t>(mesh.num_nodes()), false), moving_node = static_node;
  for (const Index i : partition.s) static_node[static_cast<std::size_t>(dofs.full_dof(i) / 3)] = true;
  for (const Index i : partition.d) moving_node[static_cast<std::size_t>(dofs.full_dof(i) / 3)] = true;
  for (const Tool& tool : tools)
    for (const int n : tool.nodes) moving_node[static_cast<std::size_t>(n)] = true;
  std::vector<Index> elements;
  for (Index e = 0; e < mesh.num_tets(); ++e)
    if (follows_the_law(materials.of(e)) && !element_touches(mesh, e, static_node) && element_touches(mesh, e, moving_node))
      elements.push_back(e);
  return elements;
}

}  // namespace

std::shared_ptr<const InternalForce> hyperelastic_force(const mesh::TetMesh& mesh, const fem::DofMap& dofs,
                                                        const fem::MaterialMap& materials, fem::Element element,
                                                        const std::vector<Tool>& tools) {
  if (!materials.nonlinear()) return nullptr;
  require_every_element_hyperelastic(mesh, materials, element);
  std::vector<Index> elements;
  for (Index e = 0; e < mesh.num_tets(); ++e)
    if (follows_the_law(materials.of(e))) elements.push_back(e);
  const bool every = static_cast<Index>(elements.size()) == mesh.num_tets();
  // K_lin: the linear elements alone (the others at zero moduli), in the linear K's pattern.
  SparseMatrix K_lin = fem::stiffness(mesh, dofs, linear_part(materials), element);
  std::string description = description_of(materials, elements, mesh.num_tets(), "");
  return std::make_shared<const HyperelasticForce>(std::shared_ptr<const fem::DofMap>(std::shared_ptr<void>(), &dofs), mesh,
                                                   materials, element, std::move(elements), std::move(K_lin), every,
                                                   std::move(description), tools);
}

std::shared_ptr<const InternalForce> hybrid_roi_force(const mesh::TetMesh& mesh, const fem::DofMap& dofs,
                                                      const fem::MaterialMap& materials, fem::Element element,
                                                      const roi::Partition& partition, const SparseMatrix& K_condensed,
                                                      const std::vector<Tool>& tools, const SplitMatrix* K_split) {
  if (!materials.nonlinear()) return nullptr;
  refuse_nodal_pressure(element);
  // The ROI's dofs as a DofMap of their own: every other dof held (at its prescribed value, or at
  // zero in the static part, which no nonlinear element reads). Both number node-major, ascending,
  // so its free dof j is partition.d[j].
  std::vector<bool> in_roi(static_cast<std::size_t>(dofs.num_full()), false);
  for (const Index i : partition.d) in_roi[static_cast<std::size_t>(dofs.full_dof(i))] = true;
  fem::Constraints held(mesh.num_nodes());
  for (Index full = 0; full < dofs.num_full(); ++full)
    if (!in_roi[static_cast<std::size_t>(full)]) held.prescribe(full / 3, static_cast<int>(full % 3), dofs.prescribed()[full]);
  auto roi_dofs = std::make_shared<const fem::DofMap>(held);
  if (roi_dofs->num_free() != partition.roi_size() || K_condensed.rows() != partition.roi_size())
    throw Error("internal: hybrid ROI: the ROI's dofs do not match the condensation's");
  // K~ less the nonlinear elements' linear stiffness: the hybrid's tangent at rest is K~.
  return law_on(std::move(roi_dofs), mesh, materials, hybrid_elements(mesh, dofs, materials, partition, tools), K_condensed,
                tools, ", the hybrid ROI's (no node in the static part)", K_split);
}

std::shared_ptr<const InternalForce> hybrid_law_uncondensed(const mesh::TetMesh& mesh, const fem::DofMap& dofs,
                                                            const fem::MaterialMap& materials, fem::Element element,
                                                            const roi::Partition& partition, const SparseMatrix& K,
                                                            const std::vector<Tool>& tools) {
  if (!materials.nonlinear()) return nullptr;
  refuse_nodal_pressure(element);
  return law_on(std::shared_ptr<const fem::DofMap>(std::shared_ptr<void>(), &dofs), mesh, materials,
                hybrid_elements(mesh, dofs, materials, partition, tools), K, tools,
                ", the hybrid ROI's, uncondensed (the full model, linear outside the ROI)");
}

}  // namespace roifem::model
