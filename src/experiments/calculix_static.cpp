// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/calculix_static.hpp"

#include <algorithm>
#include <fstream>
#include <ostream>
#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "experiments/calculix_deck.hpp"

namespace roifem::experiments {

namespace fs = std::filesystem;

namespace {

/// One *STEP per fraction, each ramping the load from the previous fraction's to its own over its
/// step time 0..1 and printing the displacements at its end.
void write_steps(const CalculixProblem& p, const std::vector<double>& fractions, bool nlgeom, std::ostream& out) {
  out << "*TIME POINTS, NAME=END\n1.0\n";
  for (const double f : fractions) {
    out << (nlgeom ? "*STEP, NLGEOM, INC=10000\n" : "*STEP\n") << "*STATIC\n0.25, 1.0, 1e-6, 0.5\n";
    if (p.newton_tolerance > 0) out << calculix::field_controls(p.newton_tolerance);
    calculix::write_loads(p, f, out);
    out << "*NODE PRINT, NSET=NALL, TIME POINTS=END\nU\n*END STEP\n";
  }
}

/// The deck: the model, then one step to the largest fraction printing at each, or one step per
/// fraction.
void write_deck(const CalculixProblem& p, const std::vector<double>& fractions, bool nlgeom, const fs::path& file) {
  std::ofstream out(file);
  out << "** roifem: the static problem for CalculiX (mm, N, MPa)\n";
  calculix::write_model(p, out);
  if (p.step_per_fraction) {
    write_steps(p, fractions, nlgeom, out);
    if (!out.flush()) throw InputError(file.string() + ": cannot write the CalculiX deck");
    return;
  }
  // The load is scaled to the largest fraction and ramped over the step time 0..1; the time
  // points are the fractions over it.
  const double top = fractions.back();
  out << "*TIME POINTS, NAME=FRACTIONS\n";
  for (double f : fractions) out << format("%.13g\n", f / top);
  out << (nlgeom ? "*STEP, NLGEOM, INC=10000\n" : "*STEP\n");
  out << format("*STATIC\n%.6g, 1.0, 1e-6, %.6g\n", fractions.front() / top / 2, fractions.front() / top);
  if (p.newton_tolerance > 0) out << calculix::field_controls(p.newton_tolerance);
  calculix::write_loads(p, top, out);
  out << "*NODE PRINT, NSET=NALL, TIME POINTS=FRACTIONS\nU\n*END STEP\n";
  if (!out.flush()) throw InputError(file.string() + ": cannot write the CalculiX deck");
}

}  // namespace

std::vector<CalculixSolution> solve_with_calculix(const CalculixProblem& p, const std::vector<double>& fractions, bool nlgeom,
                                                  const fs::path& work_dir, std::ostream& log) {
  if (fractions.empty()) throw InputError("CalculiX: no load fractions asked for");
  for (std::size_t i = 0; i < fractions.size(); ++i)
    if (!(fractions[i] > 0) || (i > 0 && !(fractions[i] > fractions[i - 1])))
      throw InputError("CalculiX: load fractions must be positive and ascending");
  const Index nodes = p.mesh->num_nodes();
  if (p.forces.size() != 3 * nodes) throw InputError("CalculiX: the forces do not match the mesh's nodes");
  fs::create_directories(work_dir);
  const std::string job = nlgeom ? "nlgeom" : "linear";
  for (const char* ext : {".dat", ".frd", ".sta", ".cvg"}) fs::remove(work_dir / (job + ext));
  write_deck(p, fractions, nlgeom, work_dir / (job + ".inp"));
  const int status = calculix::run_ccx(work_dir, job);
  const auto blocks = calculix::read_displacements(work_dir / (job + ".dat"), nodes);
  std::vector<CalculixSolution> solutions;
  const double top = fractions.back();
  for (std::size_t i = 0; i < fractions.size(); ++i) {
    if (p.step_per_fraction) {  // one block per step, in order
      if (i >= blocks.size()) break;
      solutions.push_back({fractions[i], blocks[i].second});
      continue;
    }
    // ccx prints the step time with 7 digits.
    const double t = fractions[i] / top;
    const auto it = std::find_if(blocks.begin(), blocks.end(), [&](const auto& b) { return std::abs(b.first - t) <= 1e-6; });
    if (it == blocks.end()) break;
    solutions.push_back({fractions[i], it->second});
  }
  if (solutions.empty())
    throw SolverError(
        format("CalculiX returned no solution (exit status %d): see %s", status, (work_dir / (job + ".log")).c_str()));
  if (solutions.size() < fractions.size())
    log << format("  CalculiX (%s) stopped at %.3g of the load (asked up to %.3g): see %s\n", job.c_str(),
                  solutions.back().fraction, top, (work_dir / (job + ".log")).c_str());
  return solutions;
}

}  // namespace roifem::experiments
