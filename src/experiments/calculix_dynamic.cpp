// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/calculix_dynamic.hpp"

#include <cmath>
#include <fstream>
#include <ostream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "experiments/calculix_deck.hpp"

namespace roifem::experiments {

namespace fs = std::filesystem;

namespace {

constexpr double t_per_kg = 1e-3;
constexpr double tonne_per_mm3 = 1e-12;  // per kg/m^3

/// The MASS elements, one per node that has mass, numbered after the solid's elements, each its
/// own element set for its *MASS card.
void write_point_masses(const CalculixDynamicProblem& p, std::ostream& out) {
  const Index solid = static_cast<Index>(p.model.mesh->tets.size());
  out << "*ELEMENT, TYPE=MASS, ELSET=POINTMASSES\n";
  for (Index n = 0; n < p.lumped_mass.size(); ++n)
    if (p.lumped_mass[n] > 0) out << format("%lld, %lld\n", static_cast<long long>(solid + n) + 1, static_cast<long long>(n) + 1);
  for (Index n = 0; n < p.lumped_mass.size(); ++n)
    if (p.lumped_mass[n] > 0)
      out << format("*ELSET, ELSET=M%lld\n%lld\n*MASS, ELSET=M%lld\n%.13g\n", static_cast<long long>(n) + 1,
                    static_cast<long long>(solid + n) + 1, static_cast<long long>(n) + 1, p.lumped_mass[n] * t_per_kg);
}

void write_dynamic_deck(const CalculixDynamicProblem& p, const fs::path& file) {
  std::ofstream out(file);
  const fem::Material& m = p.model.material;
  out << "** roifem: the dynamic problem for CalculiX (mm, N, MPa, t, s)\n";
  const bool lumped = p.mass == CalculixMass::lumped;
  // A zero density is refused; the solid's mass is then 1e-20 of the point masses'.
  const double density = lumped ? m.rho * tonne_per_mm3 * 1e-20 : m.rho * tonne_per_mm3;
  calculix::write_model(p.model, out, format("*DENSITY\n%.13g\n*DAMPING, ALPHA=%.13g, BETA=0\n", density, m.alpha));
  if (lumped) write_point_masses(p, out);
  const double t_end = static_cast<double>(p.steps) * p.dt;
  out << format("*AMPLITUDE, NAME=RAMP\n0, 0, %.13g, 1, %.13g, 1\n", p.ramp_s, std::max(2 * t_end, 2 * p.ramp_s));
  out << format("*STEP, NLGEOM, INC=%ld\n*DYNAMIC, DIRECT, ALPHA=0\n%.13g, %.13g\n", 10 * p.steps + 10, p.dt, t_end);
  if (p.model.newton_tolerance > 0) out << calculix::field_controls(p.model.newton_tolerance);
  calculix::write_loads(p.model, 1, out, "RAMP");
  out << "*NODE PRINT, NSET=NALL\nU\n*END STEP\n";
  if (!out.flush()) throw InputError(file.string() + ": cannot write the CalculiX deck");
}

}  // namespace

std::vector<Vector> solve_dynamics_with_calculix(const CalculixDynamicProblem& p, const fs::path& work_dir) {
  const Index nodes = p.model.mesh->num_nodes();
  if (p.model.forces.size() != 3 * nodes) throw InputError("CalculiX: the forces do not match the mesh's nodes");
  if (!(p.dt > 0) || p.steps < 1 || !(p.ramp_s > 0))
    throw InputError("CalculiX dynamics: dt, steps and the ramp must be positive");
  if (p.mass == CalculixMass::lumped && p.lumped_mass.size() != nodes)
    throw InputError("CalculiX dynamics: the lumped masses do not match the mesh's nodes");
  fs::create_directories(work_dir);
  const std::string job = "dynamic";
  for (const char* ext : {".dat", ".frd", ".sta", ".cvg"}) fs::remove(work_dir / (job + ext));
  write_dynamic_deck(p, work_dir / (job + ".inp"));
  const int status = calculix::run_ccx(work_dir, job);
  const auto blocks = calculix::read_displacements(work_dir / (job + ".dat"), nodes);
  std::vector<Vector> u;
  for (const auto& [t, block] : blocks) {
    // ccx prints the time with 7 digits.
    const double expected = static_cast<double>(u.size() + 1) * p.dt;
    if (std::abs(t - expected) > 1e-6 * std::max(1.0, expected))
      throw SolverError(format("CalculiX printed t = %.7g where step %zu ends at %.7g: its increments are not dt (see %s)", t,
                               u.size() + 1, expected, (work_dir / (job + ".log")).c_str()));
    u.push_back(block);
  }
  if (static_cast<long>(u.size()) < p.steps)
    throw SolverError(format("CalculiX stopped after %zu of %ld steps (exit status %d): see %s", u.size(), p.steps, status,
                             (work_dir / (job + ".log")).c_str()));
  return u;
}

}  // namespace roifem::experiments
