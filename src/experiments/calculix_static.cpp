// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/calculix_static.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <sstream>

#include "common/errors.hpp"
#include "io/csv.hpp"

namespace roifem::experiments {

namespace fs = std::filesystem;
using io::format;

namespace {

/// CalculiX's Newton controls (*CONTROLS, PARAMETERS=FIELD): R_n and C_n (the residual against the
/// mean force, the correction against the increment), q0 and qu left to CalculiX, R_P at its
/// default 0.02, and epsilon, below which it takes the residual for zero and converges whatever the
/// correction (default 1e-5: the 10-node brain's increments then stop after two iterations with a
/// 1-3% correction, 3e-5 off), then C_epsilon and C_f at their defaults.
std::string field_controls(double tolerance) {
  return format("*CONTROLS, PARAMETERS=FIELD\n%.3g, %.3g, 0, 0, 0.02, %.3g, 1e-3, 1e-8\n", tolerance, tolerance, tolerance);
}

/// The nodal forces at `scale` of the full load.
void write_loads(const CalculixProblem& p, double scale, std::ostream& out) {
  out << "*CLOAD\n";
  for (Index n = 0; n < p.mesh->num_nodes(); ++n)
    for (int c = 0; c < 3; ++c)
      if (const double f = p.forces[3 * n + c] * scale; f != 0)
        out << format("%lld, %d, %.13g\n", static_cast<long long>(n) + 1, c + 1, f);
}

/// One *STEP per fraction, each ramping the load from the previous fraction's to its own over its
/// step time 0..1 and printing the displacements at its end.
void write_steps(const CalculixProblem& p, const std::vector<double>& fractions, bool nlgeom, std::ostream& out) {
  out << "*TIME POINTS, NAME=END\n1.0\n";
  for (const double f : fractions) {
    out << (nlgeom ? "*STEP, NLGEOM, INC=10000\n" : "*STEP\n") << "*STATIC\n0.05, 1.0, 1e-6, 0.05\n";
    if (p.newton_tolerance > 0) out << field_controls(p.newton_tolerance);
    write_loads(p, f, out);
    out << "*NODE PRINT, NSET=NALL, TIME POINTS=END\nU\n*END STEP\n";
  }
}

/// The deck, in mm, N and MPa. Node and element numbers are 1-based; roifem's positive
/// orientation is C3D4's. Numbers keep 13 digits: ccx reads a field of at most 20 characters.
void write_deck(const CalculixProblem& p, const std::vector<double>& fractions, bool nlgeom, const fs::path& file) {
  std::ofstream out(file);
  const mesh::TetMesh& mesh = *p.mesh;
  out << "** roifem: the static problem for CalculiX (mm, N, MPa)\n*NODE, NSET=NALL\n";
  for (Index n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3 x = mesh.node(static_cast<int>(n)) / mm;
    out << format("%lld, %.13g, %.13g, %.13g\n", static_cast<long long>(n) + 1, x.x(), x.y(), x.z());
  }
  out << "*ELEMENT, TYPE=" << (mesh.is_quadratic() ? "C3D10" : "C3D4") << ", ELSET=EALL\n";
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    out << e + 1;
    for (const int n : mesh.tets[e]) out << ", " << n + 1;
    if (mesh.is_quadratic())
      for (const int n : mesh.midside.of_tet[e]) out << ", " << n + 1;
    out << "\n";
  }
  if (!p.fixed_nodes.empty()) {
    out << "*NSET, NSET=FIXED\n";
    for (std::size_t i = 0; i < p.fixed_nodes.size(); ++i) out << p.fixed_nodes[i] + 1 << (i % 16 == 15 ? ",\n" : ", ");
    out << "\n";
  }
  out << "*BOUNDARY\n";
  if (!p.fixed_nodes.empty()) out << "FIXED, 1, 3\n";
  for (const auto& [node, c] : p.held_components) out << format("%d, %d, %d\n", node + 1, c + 1, c + 1);
  out << "*MATERIAL, NAME=TISSUE\n";
  if (p.material.model == fem::MaterialModel::neo_hookean) {
    const double kappa = p.material.lambda + 2 * p.material.mu / 3;  // Pa
    out << "*HYPERELASTIC, NEO HOOKE\n" << format("%.13g, %.13g\n", p.material.mu / 2 * 1e-6, 2 / (kappa * 1e-6));
  } else {
    out << "*ELASTIC\n" << format("%.13g, %.13g\n", p.material.young() * 1e-6, p.material.poisson());
  }
  out << "*SOLID SECTION, ELSET=EALL, MATERIAL=TISSUE\n";
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
  if (p.newton_tolerance > 0) out << field_controls(p.newton_tolerance);
  write_loads(p, top, out);
  out << "*NODE PRINT, NSET=NALL, TIME POINTS=FRACTIONS\nU\n*END STEP\n";
  if (!out.flush()) throw InputError(file.string() + ": cannot write the CalculiX deck");
}

/// The displacement blocks of the .dat file, in the order printed, with their times.
std::vector<std::pair<double, Vector>> read_dat(const fs::path& file, Index nodes) {
  std::ifstream in(file);
  std::vector<std::pair<double, Vector>> blocks;
  Vector* current = nullptr;
  std::string line;
  while (std::getline(in, line)) {
    if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
      const auto at = line.find("time");
      const double t = std::stod(line.substr(at + 4));
      current = &blocks.emplace_back(t, Vector::Zero(3 * nodes)).second;
      continue;
    }
    std::istringstream fields(line);
    long long node = 0;
    double u[3];
    if (current && fields >> node >> u[0] >> u[1] >> u[2]) {
      if (node < 1 || node > nodes) throw SolverError(file.string() + ": node " + std::to_string(node) + " out of range");
      for (int c = 0; c < 3; ++c) (*current)[3 * (node - 1) + c] = u[c] * mm;
    } else if (!line.empty() && line.find_first_not_of(' ') != std::string::npos) {
      current = nullptr;
    }
  }
  return blocks;
}

}  // namespace

bool calculix_available() { return std::system("command -v ccx >/dev/null 2>&1") == 0; }

std::vector<CalculixSolution> solve_with_calculix(const CalculixProblem& p, const std::vector<double>& fractions, bool nlgeom,
                                                  const fs::path& work_dir, std::ostream& log) {
  if (fractions.empty()) throw InputError("CalculiX: no load fractions asked for");
  for (std::size_t i = 0; i < fractions.size(); ++i)
    if (!(fractions[i] > 0) || (i > 0 && !(fractions[i] > fractions[i - 1])))
      throw InputError("CalculiX: load fractions must be positive and ascending");
  const Index nodes = p.mesh->num_nodes();
  if (p.forces.size() != 3 * nodes) throw InputError("CalculiX: the forces do not match the mesh's nodes");
  if (!calculix_available()) throw SolverError("CalculiX (ccx) is not on the PATH: install calculix-ccx (scripts/setup.sh)");
  fs::create_directories(work_dir);
  const std::string job = nlgeom ? "nlgeom" : "linear";
  for (const char* ext : {".dat", ".frd", ".sta", ".cvg"}) fs::remove(work_dir / (job + ext));
  write_deck(p, fractions, nlgeom, work_dir / (job + ".inp"));
  const std::string command = "cd '" + work_dir.string() + "' && OMP_NUM_THREADS=2 ccx -i " + job + " > " + job + ".log 2>&1";
  const int status = std::system(command.c_str());
  const auto blocks = read_dat(work_dir / (job + ".dat"), nodes);
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
