// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/hyperelastic_force.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "solvers/sparse_positions.hpp"

namespace roifem::model {

namespace {

bool follows_the_law(const fem::Material& m) { return m.model == fem::MaterialModel::neo_hookean; }

/// The same regions with the neo-Hookean ones at zero moduli: the linear elements' K alone.
fem::MaterialMap linear_part(const fem::MaterialMap& materials) {
  return materials.mapped([&](fem::Material m) {
    if (follows_the_law(m)) m.lambda = m.mu = 0;
    return m;
  });
}

std::string description_of(std::size_t nonlinear, Index all, const char* where) {
  return std::string("neo-hookean, ") +
         (static_cast<Index>(nonlinear) == all ? std::string("every element")
                                               : std::to_string(nonlinear) + " of " + std::to_string(all) + " elements") +
         where;
}

}  // namespace

HyperelasticForce::HyperelasticForce(std::shared_ptr<const fem::DofMap> dofs, const mesh::TetMesh& mesh,
                                     const fem::MaterialMap& materials, std::vector<Index> elements, const SparseMatrix& K_lin,
                                     bool K_lin_is_zero, std::string description)
    : dofs_(std::move(dofs)),
      assembler_(mesh, *dofs_, materials, std::move(elements)),
      K_lin_(K_lin),
      K_lin_is_zero_(K_lin_is_zero),
      assembler_in_K_(solvers::positions_in(assembler_.pattern(), K_lin_)),
      element_tangent_(assembler_.pattern()),
      description_(std::move(description)) {}

void HyperelasticForce::force(const Vector& u, Vector& f) const {
  assembler_.force(dofs_->expand(u), f);
  if (!K_lin_is_zero_) f.noalias() += K_lin_ * u;
}

void HyperelasticForce::force_and_tangent(const Vector& u, Vector& f, SparseMatrix& K_t) const {
  assembler_.force_and_tangent(dofs_->expand(u), f, element_tangent_);
  if (!K_lin_is_zero_) f.noalias() += K_lin_ * u;
  add_elements_to_K_lin(1.0, K_t);
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
  f_alg.resize(u_a.size());
  assembler_.discrete_gradient(dofs_->expand(u_a), dofs_->expand(u_b), f_alg);
  if (!K_lin_is_zero_) f_alg.noalias() += K_lin_ * (0.5 * (u_a + u_b));
}

void HyperelasticForce::discrete_gradient_and_tangent(const Vector& u_a, const Vector& u_b, Vector& f_alg,
                                                      SparseMatrix& K_alg) const {
  f_alg.resize(u_a.size());
  assembler_.discrete_gradient_and_tangent(dofs_->expand(u_a), dofs_->expand(u_b), f_alg, element_tangent_);
  if (!K_lin_is_zero_) f_alg.noalias() += K_lin_ * (0.5 * (u_a + u_b));
  add_elements_to_K_lin(0.5, K_alg);
}

double HyperelasticForce::energy(const Vector& u) const {
  const double elements = assembler_.energy(dofs_->expand(u));
  return K_lin_is_zero_ ? elements : elements + 0.5 * u.dot(K_lin_ * u);
}

std::shared_ptr<const InternalForce> hyperelastic_force(const mesh::TetMesh& mesh, const fem::DofMap& dofs,
                                                        const fem::MaterialMap& materials, fem::Element element) {
  if (!materials.nonlinear()) return nullptr;
  if (element == fem::Element::nodal_pressure)
    throw InputError(
        "the nodal-pressure element does not take the neo-hookean law: give element = \"tet4\" or \"tet10\", or "
        "[material] model = \"linear\"");
  std::vector<Index> elements;
  for (Index e = 0; e < mesh.num_tets(); ++e)
    if (follows_the_law(materials.of(e))) elements.push_back(e);
  const bool every = static_cast<Index>(elements.size()) == mesh.num_tets();
  // K_lin: the linear elements alone (the others at zero moduli), in the linear K's pattern.
  SparseMatrix K_lin = fem::stiffness(mesh, dofs, linear_part(materials), element);
  std::string description = description_of(elements.size(), mesh.num_tets(), "");
  return std::make_shared<const HyperelasticForce>(std::shared_ptr<const fem::DofMap>(std::shared_ptr<void>(), &dofs), mesh,
                                                   materials, std::move(elements), std::move(K_lin), every,
                                                   std::move(description));
}

std::shared_ptr<const InternalForce> hybrid_roi_force(const mesh::TetMesh& mesh, const fem::DofMap& dofs,
                                                      const fem::MaterialMap& materials, fem::Element element,
                                                      const roi::Partition& partition, const SparseMatrix& K_condensed) {
  if (!materials.nonlinear()) return nullptr;
  if (element == fem::Element::nodal_pressure)
    throw InputError(
        "the nodal-pressure element does not take the neo-hookean law: give element = \"tet4\" or \"tet10\", or "
        "[material] model = \"linear\"");
  // The ROI's dofs as a DofMap of their own: every other dof held (at its prescribed value, or at
  // zero in the static part, which no nonlinear element reads). Both number node-major, ascending,
  // so its free dof j is partition.d[j].
  std::vector<bool> in_roi(static_cast<std::size_t>(dofs.num_full()), false);
  for (const Index i : partition.d) in_roi[static_cast<std::size_t>(dofs.full_dof(i))] = true;
  std::vector<bool> static_node(static_cast<std::size_t>(mesh.num_nodes()), false);
  for (const Index i : partition.s) static_node[static_cast<std::size_t>(dofs.full_dof(i) / 3)] = true;
  fem::Constraints held(mesh.num_nodes());
  for (Index full = 0; full < dofs.num_full(); ++full)
    if (!in_roi[static_cast<std::size_t>(full)]) held.prescribe(full / 3, static_cast<int>(full % 3), dofs.prescribed()[full]);
  auto roi_dofs = std::make_shared<const fem::DofMap>(held);
  if (roi_dofs->num_free() != partition.roi_size() || K_condensed.rows() != partition.roi_size())
    throw Error("internal: hybrid ROI: the ROI's dofs do not match the condensation's");
  // The nonlinear elements: neo-Hookean, with no node in the static part.
  std::vector<Index> elements;
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    if (!follows_the_law(materials.of(e))) continue;
    bool touches_static = false;
    for (const int n : mesh.tets[static_cast<std::size_t>(e)]) touches_static |= static_node[static_cast<std::size_t>(n)];
    if (mesh.is_quadratic())
      for (const int n : mesh.midside.of_tet[static_cast<std::size_t>(e)])
        touches_static |= static_node[static_cast<std::size_t>(n)];
    if (!touches_static) elements.push_back(e);
  }
  // K_lin = K~ - the nonlinear elements' linear stiffness (their tangent at rest, which the law's
  // linearization makes the linear one), in K~'s pattern: the hybrid's tangent at rest is K~.
  SparseMatrix K_at_rest;
  Vector f(roi_dofs->num_free());
  fem::HyperelasticAssembler(mesh, *roi_dofs, materials, elements)
      .force_and_tangent(roi_dofs->expand(Vector::Zero(roi_dofs->num_free())), f, K_at_rest);
  SparseMatrix K_lin = K_condensed;
  K_lin.makeCompressed();
  const std::vector<int> at = solvers::positions_in(K_at_rest, K_lin);
  for (std::size_t i = 0; i < at.size(); ++i) K_lin.valuePtr()[at[i]] -= K_at_rest.valuePtr()[i];
  std::string description = description_of(elements.size(), mesh.num_tets(), ", the hybrid ROI's (no node in the static part)");
  return std::make_shared<const HyperelasticForce>(std::move(roi_dofs), mesh, materials, std::move(elements), std::move(K_lin),
                                                   false, std::move(description));
}

}  // namespace roifem::model
