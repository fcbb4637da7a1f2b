// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// How far the mesh is from converged: the scenario's brain regenerated at several node counts
/// (mesh/brain_mesh.hpp: the same ellipsoid, the same named sets), the same physical loads, fixed
/// sets, material and element, and per mesh the quantities a user of the paper's model looks at:
///   opening   the static widening of the surgical opening under the loads at the run's end: the
///             area-weighted mean x-displacement of opening_right minus that of opening_left (the
///             displacement conjugate to the paper's forces, a functional that converges cleanly)
///   probe     the static displacement magnitude at the probe point (the ROI's target by default;
///             a point outside the body, as the paper's target in the opening is, reads the
///             nearest boundary point)
///   f1..f6    the six lowest eigenfrequencies (Hz) of the held brain
///   dynamic   the probe's displacement magnitude over the run (the full dynamic model, trapezoidal
///             rule at the scenario's dt): its peak, and per mesh the largest distance over the run
///             from the extrapolated history
/// Per quantity: the values, the observed order, a Richardson-extrapolated value
/// (experiments/richardson.hpp) and each mesh's error against it.
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "fem/element.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::experiments {

struct ConvergenceOptions {
  std::filesystem::path scenario;
  std::vector<Index> nodes{800, 5000, 20000, 100000};  ///< node counts asked of the mesher
  std::filesystem::path out;
  std::optional<std::string> material;  ///< a preset overriding the scenario's
  std::optional<fem::Element> element;  ///< overriding the scenario's
  std::optional<Vec3> probe;            ///< m; default the ROI's target (or ball centre)
  double slit_refinement = 1;           ///< mesh/brain_mesh.hpp: element size at the slit relative to the rest
  /// Meshes adapted to the scenario's static solution this many times at each node count (0: as
  /// generated): the recovery error estimate (fem/recovery_estimate.hpp) sets the next mesh's
  /// sizes (mesh/adapted_size_field.hpp). The estimate is for linear elements: tet10 takes the
  /// meshes adapted for nodal-pressure.
  int adapt_passes = 0;
  /// Also solve each mesh's static problem with quadratic tetrahedra by CalculiX (C3D10, straight-sided
  /// on the same nodes and edges: mesh/quadratic_mesh.hpp), reported as "opening c3d10".
  bool c3d10 = false;
  int modes = 6;
  bool dynamic = true;  ///< run the full dynamic model on each mesh
  bool plots = true;
};

struct MeshQuantities {
  Index nodes = 0, tets = 0, dofs = 0;  ///< nodes: the mesh's vertices (tet10 adds the edges' midpoints)
  double h_mm = 0;                      ///< (volume / tets)^(1/3) scaled to a regular tetrahedron's edge
  double opening_mm = 0, probe_mm = 0;
  double estimated_error = 0;   ///< the static solution's relative energy error, estimated by recovery (0 for tet10)
  double c3d10_opening_mm = 0;  ///< with ConvergenceOptions::c3d10
  Index c3d10_dofs = 0;
  double probe_outside_mm = 0;  ///< how far the probe lies outside this mesh
  std::vector<double> frequencies_hz;
  std::vector<double> probe_history_mm;  ///< per step 1..steps (empty without the dynamic run)
  double seconds = 0;                    ///< meshing, solving and running
};

/// The order the extrapolation assumes where none is observed, and the one the observed order is
/// held to: 2, a linear tetrahedron's for displacements and frequencies.
constexpr double formal_order = 2.0;

struct QuantityConvergence {
  std::string name, unit;
  std::vector<double> values;            ///< per mesh, coarse to fine
  std::optional<double> observed_order;  ///< of the three finest
  double order_used = 0;
  /// The three finest meshes show an order within half of the formal one (formal_order): only then
  /// are the extrapolation and the errors estimates, not just distances to a guess.
  bool asymptotic = false;
  double extrapolated = 0;
  std::vector<double> errors;  ///< |value - extrapolated| per mesh (dynamic: the largest over the run)
};

struct ConvergenceResults {
  std::string element, material;
  Vec3 probe = Vec3::Zero();  ///< m
  double dt = 0;
  std::vector<MeshQuantities> meshes;  ///< coarse to fine
  std::vector<QuantityConvergence> quantities;
  std::vector<double> extrapolated_history_mm;  ///< the probe over the run, extrapolated
};

/// How far the brain's opening widens under u (3N, m): the area-weighted mean x-displacement of
/// opening_right minus that of opening_left (m).
double opening_widening(const mesh::TetMesh& mesh, const Vector& u);

/// Runs the study, writes convergence.csv, probe_history.csv, the meshes (meshes/brain-N.msh,
/// reused when present) and convergence.png into options.out; the table goes to `log`. Throws
/// InputError for fewer than two sizes, sizes out of order, or a scenario whose mesh is not the
/// generated brain (tools and loads act as in the scenario, on each mesh's own nodes).
ConvergenceResults run_convergence_study(const ConvergenceOptions& options, std::ostream& log);

/// Prints the table: per quantity the values, orders, extrapolation and errors, and the coarsest
/// mesh's spatial error on the opening in mm and percent.
void print_convergence_table(const ConvergenceResults& results, std::ostream& log);
/// Writes convergence.csv and probe_history.csv.
void write_convergence_csv(const ConvergenceResults& results, const std::filesystem::path& out);

}  // namespace roifem::experiments
