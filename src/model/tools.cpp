// SPDX-License-Identifier: GPL-3.0-or-later
#include "model/tools.hpp"

#include "common/errors.hpp"
#include "model/internal_force.hpp"

namespace roifem::model {

ToolSet::ToolSet(std::vector<Tool> tools, const SparseMatrix& coupling, DenseMatrix self, LoadHistory load_at_tools)
    : tools_(std::move(tools)), coupling_(coupling), self_(std::move(self)), load_at_tools_(std::move(load_at_tools)) {
  const Index rows = 3 * count();
  if (coupling_.rows() != rows || self_.rows() != rows || self_.cols() != rows || load_at_tools_.size() != rows)
    throw Error("internal: a tool set's matrices do not match its tools");
}

std::vector<std::pair<Vec3, Ramp>> ToolPath::terms() const {
  if (!trajectory) return {{displacement, ramp}};
  return {{Vec3::UnitX(), (*trajectory)[0]}, {Vec3::UnitY(), (*trajectory)[1]}, {Vec3::UnitZ(), (*trajectory)[2]}};
}

std::vector<double> ToolPath::kinks_after(double t) const {
  std::vector<double> kinks = trajectory ? (*trajectory)[0].kinks_after(t) : ramp.kinks_after(t);  // shared sample times
  return kinks;
}

Vector ToolSet::positions(double t) const {
  Vector g(3 * count());
  for (Index a = 0; a < count(); ++a) g.segment<3>(3 * a) = tools_[static_cast<std::size_t>(a)].path.at(t);
  return g;
}

Vector ToolSet::forces(const Eigen::Ref<const Vector>& u, double t) const {
  return forces(coupling_ * u, self_ * positions(t), u, t);
}

Vector ToolSet::forces(const Vector& coupled, const Vector& self_g, const Eigen::Ref<const Vector>& u, double t) const {
  Vector F = coupled + self_g - load_at_tools_.at(t);
  if (law_ && law_->has_motion()) F += law_->tool_force_correction(t, u);
  return F;
}

ToolSet ToolSet::with_law(std::shared_ptr<const InternalForce> law) const {
  ToolSet out = *this;
  out.law_ = std::move(law);
  return out;
}

double ToolSet::coupling_energy(const Eigen::Ref<const Vector>& u, double t) const {
  const Vector g = positions(t);
  return g.dot(coupling_ * u) + 0.5 * g.dot(self_ * g);
}

ToolSet ToolSet::renumbered(Index new_size, const std::vector<Index>& new_index) const {
  if (static_cast<Index>(new_index.size()) != coupling_.cols()) throw Error("internal: a tool renumbering of the wrong size");
  std::vector<Eigen::Triplet<double>> entries;
  for (Index j = 0; j < coupling_.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(coupling_, j); it; ++it) {
      const Index to = new_index[static_cast<std::size_t>(it.col())];
      if (to < 0) throw Error("internal: a tool coupled to an unknown the renumbering drops");
      entries.emplace_back(it.row(), to, it.value());
    }
  SparseMatrix coupling(coupling_.rows(), new_size);
  coupling.setFromTriplets(entries.begin(), entries.end());
  return {tools_, coupling, self_, load_at_tools_};
}

ToolSet ToolSet::with_ramp(const Ramp& ramp) const {
  ToolSet out = *this;
  for (auto& tool : out.tools_) {
    if (tool.path.trajectory) throw Error("tool '" + tool.name + "' follows a trajectory: its ramp cannot be replaced");
    tool.path.ramp = ramp;
  }
  out.load_at_tools_ = load_at_tools_.with_ramp(ramp);
  if (law_) out.law_ = law_->with_ramp(ramp);
  return out;
}

}  // namespace roifem::model
