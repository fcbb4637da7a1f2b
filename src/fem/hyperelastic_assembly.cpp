// SPDX-License-Identifier: GPL-3.0-or-later
#include "fem/hyperelastic_assembly.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <span>
#include <type_traits>
#include <variant>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "fem/assembly.hpp"
#include "fem/hyperelastic_element.hpp"
#include "fem/tet4_excess_batch.hpp"

namespace roifem::fem {

namespace {

std::size_t as_size(Index i) { return static_cast<std::size_t>(i); }

std::vector<Index> all_elements(const mesh::TetMesh& mesh) {
  std::vector<Index> all(as_size(mesh.num_tets()));
  std::iota(all.begin(), all.end(), Index{0});
  return all;
}

}  // namespace

HyperelasticAssembler::HyperelasticAssembler(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials)
    : HyperelasticAssembler(mesh, dofs, materials, all_elements(mesh)) {}

HyperelasticAssembler::HyperelasticAssembler(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials,
                                             std::vector<Index> elements)
    : HyperelasticAssembler(mesh, dofs, materials, std::move(elements), mesh.is_quadratic() ? Element::tet10 : Element::tet4) {}

HyperelasticAssembler::HyperelasticAssembler(const mesh::TetMesh& mesh, const DofMap& dofs, const MaterialMap& materials,
                                             std::vector<Index> elements, Element element)
    : mesh_(mesh), dofs_(dofs), materials_(materials), elements_(std::move(elements)) {
  for (const Index e : elements_)
    if (e < 0 || e >= mesh.num_tets())
      throw InputError("hyperelastic assembly: tetrahedron " + std::to_string(e) + " is not in the mesh");
  if (mesh.is_quadratic() != (element == Element::tet10))
    throw Error("internal: hyperelastic assembly: " + std::string(element_name(element)) + " on a " +
                (mesh.is_quadratic() ? "quadratic" : "linear") + " mesh");
  for (const Material& m : materials_.materials()) laws_.push_back(hyperelastic_law(m));
  if (element == Element::nodal_pressure) {
    std::vector<double> kappa(as_size(mesh.num_tets()));
    for (Index e = 0; e < mesh.num_tets(); ++e)
      kappa[as_size(e)] = std::visit([](const auto& law) { return law.kappa(); }, laws_[materials_.index_of(e)]);
    nodal_ = std::make_shared<const NodalVolumetricEnergy>(mesh, dofs, std::move(kappa));
    for (HyperelasticLaw& law : laws_) law = std::visit([](const auto& l) { return HyperelasticLaw(l.deviatoric_part()); }, law);
    pattern_ = nodal_->pattern();
  } else {
    pattern_ = StiffnessAssembler(mesh, dofs).stiffness(materials);
    std::fill(pattern_.valuePtr(), pattern_.valuePtr() + pattern_.nonZeros(), 0.0);
  }
  cache_positions();
  law_of_.reserve(elements_.size());
  bool all_neo_hookean = true;
  for (const Index e : elements_) {
    law_of_.push_back(static_cast<std::uint16_t>(materials_.index_of(e)));
    all_neo_hookean = all_neo_hookean && std::holds_alternative<NeoHookean>(laws_[law_of_.back()]);
  }
  if (!mesh.is_quadratic()) {
    tet4_geometry_.reserve(elements_.size());
    for (const Index e : elements_) {
      const auto& c = mesh.tets[as_size(e)];
      tet4_geometry_.push_back(tet4_geometry(mesh.node(c[0]), mesh.node(c[1]), mesh.node(c[2]), mesh.node(c[3])));
    }
    if (all_neo_hookean) batch_excess();
  }
}

std::span<const int> HyperelasticAssembler::nodes_of(std::size_t slot, std::array<int, 10>& nodes) const {
  const Index e = elements_[slot];
  const auto& c = mesh_.tets[as_size(e)];
  std::copy(c.begin(), c.end(), nodes.begin());
  if (!mesh_.is_quadratic()) return {nodes.data(), 4};
  std::copy(mesh_.midside.of_tet[as_size(e)].begin(), mesh_.midside.of_tet[as_size(e)].end(), nodes.begin() + 4);
  return {nodes.data(), 10};
}

void HyperelasticAssembler::cache_positions() {
  const std::size_t n = mesh_.is_quadratic() ? 30 : 12, per_element = n * n;
  constexpr std::size_t budget = std::size_t{32} << 20;
  if (elements_.size() * per_element > budget) return;
  positions_.resize(elements_.size() * per_element);
  const int* outer = pattern_.outerIndexPtr();
  const int* inner = pattern_.innerIndexPtr();
  std::array<int, 10> buffer{};
  for (std::size_t slot = 0; slot < elements_.size(); ++slot) {
    const auto nodes = nodes_of(slot, buffer);
    int* at = positions_.data() + slot * per_element;
    for (std::size_t b = 0; b < nodes.size(); ++b)
      for (int k = 0; k < 3; ++k) {
        const int column = dofs_.free_dof(nodes[b], k);
        for (std::size_t a = 0; a < nodes.size(); ++a)
          for (int i = 0; i < 3; ++i) {
            const int row = dofs_.free_dof(nodes[a], i);
            *at++ = row < 0 || column < 0
                        ? -1
                        : static_cast<int>(std::lower_bound(inner + outer[column], inner + outer[column + 1], row) - inner);
          }
      }
  }
}

/// Calls visit(slot, nodes, response) for every element, with the element's nodes (corners, then
/// midpoints) and the response that evaluate(geometry, law, gather) returns, gather(u_full) being
/// the element's values of a full displacement; an inverted element is a ModelError.
template <class Evaluator, class Visit>
void HyperelasticAssembler::for_each_element(Evaluator&& evaluate, Visit&& visit) const {
  std::array<int, 10> buffer{};
  for (std::size_t slot = 0; slot < elements_.size(); ++slot) {
    const Index e = elements_[slot];
    const auto& c = mesh_.tets[as_size(e)];
    const auto nodes = nodes_of(slot, buffer);
    auto check = [&](const auto& r) {
      if (!(r.min_J > 0))
        throw ModelError(format("tetrahedron %lld (nodes %d %d %d %d) has inverted: det F = %.4g <= 0", static_cast<long long>(e),
                                c[0], c[1], c[2], c[3], r.min_J));
    };
    std::visit(
        [&](const auto& law) {
          if (nodes.size() == 4) {
            auto gather = [&](const Vector& u_full) {
              Eigen::Matrix<double, 12, 1> ue;
              for (int a = 0; a < 4; ++a) ue.segment<3>(3 * a) = u_full.segment<3>(3 * nodes[as_size(a)]);
              return ue;
            };
            const auto r = evaluate(tet4_geometry_[slot], law, gather);
            check(r);
            visit(slot, nodes, r);
          } else {
            auto gather = [&](const Vector& u_full) {
              Eigen::Matrix<double, 30, 1> ue;
              for (int a = 0; a < 10; ++a) ue.segment<3>(3 * a) = u_full.segment<3>(3 * nodes[as_size(a)]);
              return ue;
            };
            const auto r =
                evaluate(tet10_geometry(mesh_.node(c[0]), mesh_.node(c[1]), mesh_.node(c[2]), mesh_.node(c[3])), law, gather);
            check(r);
            visit(slot, nodes, r);
          }
        },
        laws_[law_of_[slot]]);
  }
}

template <class Visit>
void HyperelasticAssembler::for_each_element(const Vector& u_full, Evaluate what, Visit&& visit) const {
  check_size(u_full);
  for_each_element(
      [&](const auto& geometry, const auto& law, const auto& gather) {
        if constexpr (std::is_same_v<std::decay_t<decltype(geometry)>, Tet4Geometry>)
          return tet4_hyperelastic(geometry, law, gather(u_full), what);
        else
          return tet10_hyperelastic(geometry, law, gather(u_full), what);
      },
      visit);
}

void HyperelasticAssembler::check_size(const Vector& u_full) const {
  if (u_full.size() != 3 * mesh_.num_nodes())
    throw InputError(format("hyperelastic assembly: %lld displacement values for %lld nodes",
                            static_cast<long long>(u_full.size()), static_cast<long long>(mesh_.num_nodes())));
}

void HyperelasticAssembler::scatter(std::size_t slot, std::span<const int> nodes, const Eigen::Ref<const DenseMatrix>& K_e,
                                    SparseMatrix& K) const {
  double* values = K.valuePtr();
  const Index n = 3 * static_cast<Index>(nodes.size());
  if (!positions_.empty()) {
    const int* at = positions_.data() + slot * as_size(n * n);
    for (Index j = 0; j < n; ++j)
      for (Index i = 0; i < n; ++i, ++at)
        if (*at >= 0) values[*at] += K_e(i, j);
    return;
  }
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  for (std::size_t b = 0; b < nodes.size(); ++b)
    for (int k = 0; k < 3; ++k) {
      const int column = dofs_.free_dof(nodes[b], k);
      if (column < 0) continue;
      const int* begin = inner + outer[column];
      const int* end = inner + outer[column + 1];
      for (std::size_t a = 0; a < nodes.size(); ++a) {
        // A node's free components are adjacent rows of every column (the free numbering is
        // node-major): one search finds the first, the others follow.
        const int node = nodes[a];
        int first = -1;
        for (int i = 0; i < 3 && first < 0; ++i) first = dofs_.free_dof(node, i);
        if (first < 0) continue;
        double* target = values + (std::lower_bound(begin, end, first) - inner);
        const Index row0 = 3 * static_cast<Index>(a), col = 3 * static_cast<Index>(b) + k;
        for (int i = 0; i < 3; ++i)
          if (dofs_.free_dof(node, i) >= 0) *target++ += K_e(row0 + i, col);
      }
    }
}

void HyperelasticAssembler::force(const Vector& u_full, Eigen::Ref<Vector> f_int) const {
  add_forces(u_full, Evaluate::force, f_int);
  if (nodal_) nodal_->add_force(u_full, f_int);
}

void HyperelasticAssembler::excess_force_free(const Vector& u_free, Eigen::Ref<Vector> g) const {
  if (u_free.size() != dofs_.num_free())
    throw InputError(format("hyperelastic assembly: %lld free displacement values for %lld free dofs",
                            static_cast<long long>(u_free.size()), static_cast<long long>(dofs_.num_free())));
  if (nodal_ || (excess_batches_.empty() && !elements_.empty())) {  // tet10, nodal pressures, or a law other than neo-Hookean
    const Vector u_full = dofs_.prescribed() + dofs_.expand_homogeneous(u_free);
    add_forces(u_full, Evaluate::excess, g);
    if (nodal_) nodal_->add_excess_force(u_full, g);
    return;
  }
  // A haptic tick's loop: kTet4Lanes elements at a time (fem/tet4_excess_batch.hpp), their dofs
  // looked up once (ExcessBatch), the free displacement read where it lies (a hybrid ROI's few
  // thousand dofs stay in cache).
  g.setZero();
  const Vector& prescribed = dofs_.prescribed();
  double ue[12][kTet4Lanes], excess[12][kTet4Lanes], J[kTet4Lanes];
  for (std::size_t batch = 0; batch < excess_batches_.size(); ++batch) {
    const ExcessBatch& b = excess_batches_[batch];
    for (int k = 0; k < 12; ++k)
      for (int l = 0; l < kTet4Lanes; ++l) {
        const int row = b.rows[k][l], full = b.full[k][l];
        ue[k][l] = row >= 0 ? u_free[row] : full >= 0 ? prescribed[full] : 0.0;
      }
    tet4_excess_force_batch(b.law, ue, excess, J);
    for (int l = 0; l < kTet4Lanes; ++l)
      if (!(J[l] > 0)) {
        const std::size_t slot = batch * kTet4Lanes + as_size(l);
        const auto& c = mesh_.tets[as_size(elements_[slot])];
        throw ModelError(format("tetrahedron %lld (nodes %d %d %d %d) has inverted: det F = %.4g <= 0",
                                static_cast<long long>(elements_[slot]), c[0], c[1], c[2], c[3], J[l]));
      }
    for (int k = 0; k < 12; ++k)
      for (int l = 0; l < kTet4Lanes; ++l)
        if (const int row = b.rows[k][l]; row >= 0) g[row] += excess[k][l];
  }
}

void HyperelasticAssembler::batch_excess() {
  const std::size_t count = elements_.size();
  excess_batches_.resize((count + kTet4Lanes - 1) / kTet4Lanes);
  for (std::size_t slot = 0; slot < excess_batches_.size() * kTet4Lanes; ++slot) {
    ExcessBatch& b = excess_batches_[slot / kTet4Lanes];
    const auto l = static_cast<int>(slot % kTet4Lanes);
    for (int k = 0; k < 12; ++k) b.rows[k][l] = b.full[k][l] = -1;
    if (slot >= count) continue;  // a lane with no element: zero geometry, no dofs
    const auto& c = mesh_.tets[as_size(elements_[slot])];
    for (int k = 0; k < 12; ++k) {
      b.rows[k][l] = dofs_.free_dof(c[as_size(k / 3)], k % 3);
      b.full[k][l] = 3 * c[as_size(k / 3)] + k % 3;
    }
    const Tet4Geometry& geometry = tet4_geometry_[slot];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) b.law.grad[a][i][l] = geometry.grad(a, i);
    b.law.volume[l] = std::abs(geometry.volume);
    const auto& law = std::get<NeoHookean>(laws_[law_of_[slot]]);
    b.law.mu[l] = law.mu();
    b.law.kappa[l] = law.kappa();
    b.law.lambda[l] = law.kappa() - 2.0 / 3.0 * law.mu();
  }
}

void HyperelasticAssembler::add_forces(const Vector& u_full, Evaluate what, Eigen::Ref<Vector> f) const {
  f.setZero();
  for_each_element(u_full, what, [&](std::size_t, std::span<const int> nodes, const auto& r) {
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int i = 0; i < 3; ++i)
        if (const int row = dofs_.free_dof(nodes[a], i); row >= 0) f[row] += r.force[3 * static_cast<Index>(a) + i];
  });
}

void HyperelasticAssembler::force_and_tangent(const Vector& u_full, Eigen::Ref<Vector> f_int, SparseMatrix& K_t) const {
  if (K_t.nonZeros() != pattern_.nonZeros() || K_t.rows() != pattern_.rows()) K_t = pattern_;
  std::fill(K_t.valuePtr(), K_t.valuePtr() + K_t.nonZeros(), 0.0);
  f_int.setZero();
  for_each_element(u_full, Evaluate::force_and_tangent, [&](std::size_t slot, std::span<const int> nodes, const auto& r) {
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int i = 0; i < 3; ++i)
        if (const int row = dofs_.free_dof(nodes[a], i); row >= 0) f_int[row] += r.force[3 * static_cast<Index>(a) + i];
    scatter(slot, nodes, r.tangent, K_t);
  });
  if (nodal_) nodal_->add_force_and_tangent(u_full, f_int, K_t);
}

void HyperelasticAssembler::discrete_gradient(const Vector& u_a_full, const Vector& u_b_full, Eigen::Ref<Vector> f_alg,
                                              SparseMatrix* K_alg) const {
  if (nodal_)
    throw InputError(
        "the discrete gradient (energy-momentum) is not formed for the nodal-pressure element at finite strain: give element = "
        "\"tet4\" or \"tet10\", or another method");
  check_size(u_a_full);
  check_size(u_b_full);
  const Evaluate what = K_alg ? Evaluate::force_and_tangent : Evaluate::force;
  if (K_alg) {
    if (K_alg->nonZeros() != pattern_.nonZeros() || K_alg->rows() != pattern_.rows()) *K_alg = pattern_;
    std::fill(K_alg->valuePtr(), K_alg->valuePtr() + K_alg->nonZeros(), 0.0);
  }
  f_alg.setZero();
  for_each_element(
      [&](const auto& geometry, const auto& law, const auto& gather) {
        if constexpr (std::is_same_v<std::decay_t<decltype(geometry)>, Tet4Geometry>)
          return tet4_discrete_gradient(geometry, law, gather(u_a_full), gather(u_b_full), what);
        else
          return tet10_discrete_gradient(geometry, law, gather(u_a_full), gather(u_b_full), what);
      },
      [&](std::size_t slot, std::span<const int> nodes, const auto& r) {
        for (std::size_t a = 0; a < nodes.size(); ++a)
          for (int i = 0; i < 3; ++i)
            if (const int row = dofs_.free_dof(nodes[a], i); row >= 0) f_alg[row] += r.force[3 * static_cast<Index>(a) + i];
        if (K_alg) scatter(slot, nodes, r.tangent, *K_alg);
      });
}

void HyperelasticAssembler::discrete_gradient(const Vector& u_a_full, const Vector& u_b_full, Eigen::Ref<Vector> f_alg) const {
  discrete_gradient(u_a_full, u_b_full, f_alg, nullptr);
}

void HyperelasticAssembler::discrete_gradient_and_tangent(const Vector& u_a_full, const Vector& u_b_full,
                                                          Eigen::Ref<Vector> f_alg, SparseMatrix& K_alg) const {
  discrete_gradient(u_a_full, u_b_full, f_alg, &K_alg);
}

double HyperelasticAssembler::energy(const Vector& u_full) const {
  double total = 0;
  for_each_element(u_full, Evaluate::energy, [&](std::size_t, std::span<const int>, const auto& r) { total += r.energy; });
  if (nodal_) total += nodal_->energy(u_full);
  return total;
}

}  // namespace roifem::fem
