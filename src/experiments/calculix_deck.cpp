// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/calculix_deck.hpp"

#include <cstdlib>
#include <fstream>
#include <ostream>
#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"

namespace roifem::experiments {

namespace fs = std::filesystem;

bool calculix_available() { return std::system("command -v ccx >/dev/null 2>&1") == 0; }

namespace calculix {

std::string field_controls(double tolerance) {
  return format("*CONTROLS, PARAMETERS=FIELD\n%.3g, %.3g, 0, 0, 0.02, %.3g, 1e-3, 1e-8\n", tolerance, tolerance, tolerance);
}

void write_loads(const CalculixProblem& p, double scale, std::ostream& out, const std::string& amplitude) {
  out << (amplitude.empty() ? std::string("*CLOAD\n") : "*CLOAD, AMPLITUDE=" + amplitude + "\n");
  for (Index n = 0; n < p.mesh->num_nodes(); ++n)
    for (int c = 0; c < 3; ++c)
      if (const double f = p.forces[3 * n + c] * scale; f != 0)
        out << format("%lld, %d, %.13g\n", static_cast<long long>(n) + 1, c + 1, f);
}

void write_model(const CalculixProblem& p, std::ostream& out, const std::string& material_lines) {
  const mesh::TetMesh& mesh = *p.mesh;
  out << "*NODE, NSET=NALL\n";
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
  } else if (p.material.model == fem::MaterialModel::ogden) {
    // CalculiX's OGDEN, N=1: mu_1 (MPa), alpha_1, D1 (1/MPa); more terms would need its D2.. too.
    if (p.material.ogden.size() != 1)
      throw InputError("the CalculiX deck takes a one-term Ogden law; this material has " +
                       std::to_string(p.material.ogden.size()) + " terms");
    const double kappa = p.material.lambda + 2 * p.material.mu / 3;  // Pa
    out << "*HYPERELASTIC, OGDEN, N=1\n"
        << format("%.13g, %.13g, %.13g\n", p.material.ogden[0].mu * 1e-6, p.material.ogden[0].alpha, 2 / (kappa * 1e-6));
  } else {
    out << "*ELASTIC\n" << format("%.13g, %.13g\n", p.material.young() * 1e-6, p.material.poisson());
  }
  out << material_lines << "*SOLID SECTION, ELSET=EALL, MATERIAL=TISSUE\n";
}

int run_ccx(const fs::path& work_dir, const std::string& job) {
  if (!calculix_available()) throw SolverError("CalculiX (ccx) is not on the PATH: install calculix-ccx (scripts/setup.sh)");
  const std::string command =
      "cd '" + work_dir.string() + "' && OMP_NUM_THREADS=${OMP_NUM_THREADS:-2} ccx -i " + job + " > " + job + ".log 2>&1";
  return std::system(command.c_str());
}

std::vector<std::pair<double, Vector>> read_displacements(const fs::path& file, Index nodes) {
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

}  // namespace calculix
}  // namespace roifem::experiments
