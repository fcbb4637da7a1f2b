// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// What `roifem serve` simulates: the scenario's brain as several models, each prepared once (its
/// condensation and the haptic loop's factor) so that the page switches between them live:
///   the full dynamic model, and with an [roi] the ROI condensed by each reduction of the static
///   part that keeps the uncut mesh's linear model exact in its own terms (static, guyan,
///   craig-bampton: POD learns its basis from the scenario's loads, not from a hand);
///   and at large deformation, the same with the neo-Hookean law (a name's "-neo-hookean"): the
///   whole brain (full-neo-hookean) or the hybrid ROI (static-neo-hookean: the ROI's elements
///   neo-Hookean over the linear condensed remainder, model/hyperelastic_force.hpp), ticked by
///   modified Newton on the linear K_eff with a stated budget (integrators/haptic_trapezoid.hpp);
///   and models the page's scalpel cuts (a name's "-cut": full-cut, static-cut), each its own copy
///   of the linear full model or static condensation, cut in place (simulation/cuts/element_cuts.hpp)
///   while the others stay whole.
/// A model's name states its law, whatever the scenario's [material] model says; the scenario's
/// moduli are the law's small-strain moduli.
/// The scenario's own [[tool]]s and [[cut]]s are left out (the page's hand is the tool); its
/// mesh, material, supports, loads and ROI are kept. The hand holds, as `roifem run`'s footprint
/// tool does, the boundary nodes within a radius of the point it picks (scenario/README.md).
#include <array>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "integrators/haptic_trapezoid.hpp"
#include "scenario/scenario.hpp"
#include "simulation/cuts/element_cuts.hpp"
#include "simulation/scenario_model.hpp"

namespace roifem::serve {

/// The mesh's surface as the page draws it: its boundary nodes (vertices) and faces.
struct SurfaceView {
  std::vector<int> nodes;                     ///< mesh nodes, ascending (vertex k is nodes[k])
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices, outward
  std::vector<std::uint8_t> flags;            ///< per vertex: bit 0 fixed, bit 1 + k in model k's ROI
};

/// The kinds of a served model, one table that the plan, --models, the page's names and the
/// messages read: a model's name is its base (full, or a reduction's label) and its kind's suffix.
enum class ModelKind { linear, neo_hookean, cut };
struct ModelKindInfo {
  ModelKind kind;
  std::string_view suffix;  ///< after the base ("" for the linear kind)
  fem::MaterialModel law;
  bool cut;  ///< the page's scalpel cuts it (a copy of the linear model, cut in place)
};
inline constexpr std::array<ModelKindInfo, 3> model_kinds{
    {{ModelKind::linear, "", fem::MaterialModel::linear, false},
     {ModelKind::neo_hookean, "-neo-hookean", fem::MaterialModel::neo_hookean, false},
     {ModelKind::cut, "-cut", fem::MaterialModel::linear, true}}};
constexpr const ModelKindInfo& model_kind(ModelKind kind) {
  for (const ModelKindInfo& k : model_kinds)
    if (k.kind == kind) return k;
  return model_kinds[0];
}
/// The kind a model's name states (its suffix, the table's; no suffix: linear) and its base.
std::pair<const ModelKindInfo*, std::string> kind_of_name(std::string_view name);
/// A model's name: its base and its kind's suffix.
std::string model_name(std::string_view base, ModelKind kind);

/// What a stroke did to a cut model (LiveModel::cut): the tetrahedra it removed, or why it took
/// nothing; and whether the grab it was taken during had to end.
struct LiveCutResult {
  std::optional<simulation::CutEvent> taken;
  std::string why_not;             ///< set when nothing was taken: the page says it
  bool refused = false;            ///< the rule or the model refused it (else there was nothing to take)
  std::string grab_ended_because;  ///< the haptic loop's correction failed: the grab ends (empty: it goes on)
};

/// What the physics thread alone touches once the server runs (built before it starts). A cut
/// model's system is cut in place here, and made whole again by a fresh one; another model's never
/// changes after it is built, and the comparison's thread reads it as its reference.
struct LivePhysics {
  std::shared_ptr<simulation::ScenarioModel> model;
  std::unique_ptr<integrators::HapticTrapezoid> haptic;
  /// A cut model's (ModelKind::cut): the mesh as the cuts left it and what a removal changes, the
  /// nodes of removed tetrahedra, and whether the haptic loop's factor predates a cut taken while
  /// no grab held the model.
  std::unique_ptr<simulation::ElementCuts> cuts;
  std::vector<char> on_cut;
  bool haptic_stale = false;
};

/// What the display (the server's network thread) alone touches: the model it draws (the physics'
/// own object until the model is made whole: then the display takes the fresh one when it learns
/// of it, the old one kept alive while it still draws from it), the surface drawn, the tetrahedra
/// it bounds, and per vertex and component its place among the unknowns u (-1: none), for the
/// static part its place in u_s (-1: none), with the static part's last recovered values.
struct LiveDisplay {
  std::shared_ptr<simulation::ScenarioModel> model;
  std::shared_ptr<const SurfaceView> view;
  std::vector<bool> shown_tets;
  std::vector<Index> surface_unknown, surface_static;
  std::vector<float> static_surface_mm;
};

/// One model of the page: what it is (set once when built, read by every thread), its physics
/// and its display, each one thread's.
struct LiveModel {
  /// "full", or the reduction's label ("static", "guyan", "craig-bampton-10"), with its kind's
  /// suffix (model_kinds)
  std::string name;
  std::string description;
  fem::MaterialModel law = fem::MaterialModel::linear;
  condensation::Reduction reduction;  ///< with an ROI
  scenario::Scenario built_from;      ///< the served scenario as this model is built from it
  Index unknowns = 0;
  std::size_t roi_size = 0;  ///< the ROI's nodes (0: a full model)
  std::vector<char> in_roi;  ///< per mesh node: an unknown of this model's ROI (the full model: every free node)
  bool cut_model = false;
  LivePhysics physics;
  LiveDisplay display;
  bool condensed() const { return roi_size > 0; }
  bool nonlinear() const { return law != fem::MaterialModel::linear; }
  bool cuttable() const { return cut_model; }
  /// The physics thread: cuts the tetrahedra `crossed` (ascending: what a stroke's blade crosses)
  /// out of this cut model, live, by the element cuts' one rule (the static part, the hand's nodes
  /// `hand`, the last of the ROI: simulation/cuts/element_cuts.hpp) and removal. During a grab
  /// (`grab`: its state) the haptic loop's factor takes the change by its correction; between grabs
  /// the state is at rest; either way the next pick factors the cut model afresh.
  LiveCutResult cut(const std::vector<Index>& crossed, model::State* grab, const std::vector<int>& hand);
};

/// A footprint the hand may hold in a model: its mesh nodes and their dofs in the model's system.
struct Grip {
  Vec3 center_mm = Vec3::Zero();  ///< as the page sent it (the replay's center_mm, exactly)
  std::vector<int> nodes;
  std::vector<std::array<Index, 3>> dofs;
};

/// The haptic loop's rate and a neo-Hookean model's Newton budget: the command line's where it
/// gives them, else the scenario's [haptic] table's, else 1 kHz and 2 iterations a tick.
struct HapticSettings {
  double rate_hz = 1000;
  integrators::HapticNewton newton;
};
HapticSettings haptic_settings(const scenario::Scenario& scenario, std::optional<double> rate_hz,
                               std::optional<int> newton_iterations, double newton_tolerance);

/// What a grab on the page feels beside the hand: by default the unloaded brain (the scenario's
/// [[load]]s, ramping during every grab, turned the paper's 16 mN wall forces on under the hand and
/// inverted the hybrid ROI within seconds); `kept`: the scenario's loads, ramping from each grab's
/// start as in `roifem run` (serve --loads). The page and the replay say which.
enum class SceneLoads { left_out, kept };

class LiveScene {
 public:
  /// Reads the mesh, builds and condenses each model and factors its haptic loop at `rate_hz`.
  /// `radius_mm`: the hand's footprint. `models`: "full" and reduction labels ("static", "guyan",
  /// "craig-bampton-10"), each with a kind's suffix (model_kinds) or none; empty: full, static, guyan,
  /// craig-bampton-10, static-neo-hookean and static-cut (a neo-Hookean scenario's: full-neo-hookean
  /// and static-neo-hookean first; without an [roi], full and full-cut). InputError for an unknown
  /// name, POD, a reduction without an [roi], the neo-Hookean law with a reduction by modes, or a
  /// cut model other than full-cut and static-cut.
  /// `newton`: the neo-Hookean models' iterations per tick; `loads`: the scenario's [[load]]s left
  /// out or kept (SceneLoads). Progress lines go to `log`.
  LiveScene(const scenario::Scenario& scenario, double rate_hz, double radius_mm, const std::vector<std::string>& models,
            std::ostream& log, integrators::HapticNewton newton = {}, SceneLoads loads = SceneLoads::left_out);
  LiveScene(const LiveScene&) = delete;
  LiveScene& operator=(const LiveScene&) = delete;

  const scenario::Scenario& scenario() const { return scenario_; }
  std::vector<LiveModel>& models() { return models_; }
  const std::vector<LiveModel>& models() const { return models_; }
  const mesh::TetMesh& mesh() const { return first_->mesh; }
  /// The uncut mesh's surface (where the hand may pick), and model k's as the display draws it
  /// (a cut model's as its cuts left it: the display's thread alone).
  const SurfaceView& surface() const { return *surface_; }
  const SurfaceView& surface(std::size_t k) const { return *models_.at(k).display.view; }
  std::shared_ptr<const SurfaceView> view_of(std::size_t k) const { return models_.at(k).display.view; }
  /// The display's thread: model k's surface without the tetrahedra `removed` (ascending), as
  /// the physics thread cut them (its vertices' places follow).
  void cut_surface(std::size_t k, const std::vector<Index>& removed);
  /// The physics thread: cut model k made whole again (a fresh model, its cuts' record and its haptic
  /// loop's factor; the display's still draws from the old one). Returns the fresh model.
  std::shared_ptr<simulation::ScenarioModel> make_whole(std::size_t k);
  /// The display's thread: model k drawn whole again, from `fresh` (make_whole's).
  void show_whole(std::size_t k, std::shared_ptr<simulation::ScenarioModel> fresh);
  double dt() const { return dt_; }
  /// The loads a grab feels beside the hand, in words for the page ("none: ...", or the kept ones).
  const std::string& loads_said() const { return loads_said_; }
  double radius_mm() const { return radius_mm_; }
  /// The mesh's bounding box (m): targets are clamped to it, widened by the largest reach.
  const Eigen::AlignedBox3d& box() const { return box_; }
  const integrators::HapticNewton& newton() const { return newton_; }
  /// The model a page starts on: the first ROI model where the scenario has an [roi] (what it was
  /// written for), else the first.
  std::size_t default_model() const;
  /// The model Compare holds model k's force against: the full model with k's law, uncut (none
  /// for a full model, a cut model, or when that one is not prepared).
  std::optional<std::size_t> reference_of(std::size_t k) const;
  /// The served scenario as model k is built from it: its law on every material.
  scenario::Scenario scenario_of(std::size_t k) const;

  /// The footprint at `center_mm` in model `k`, or why the hand cannot hold it there (no boundary
  /// node of the uncut surface within the radius, a fixed node, a node or a neighbour outside the
  /// ROI). A cut model's grip is refused by the physics thread where it holds a node of a removed
  /// tetrahedron (PhysicsLoop).
  std::variant<Grip, std::string> grip(std::size_t k, const Vec3& center_mm) const;
  /// Model k's displacement of every surface vertex (mm), from its state u at time t: the ROI's
  /// unknowns directly; the static part recovered (u_s = K_ss^-1 (f_s - K_sI u_I), one solve with
  /// the static part's factor) when `recover_static`, else as it was last recovered. Not
  /// thread-safe per model (the recovery writes the factor's workspace): the display's thread alone.
  void surface_displacement(std::size_t k, const Vector& u, double t, bool recover_static, std::vector<float>& out_mm);

 private:
  scenario::Scenario scenario_;
  std::vector<LiveModel> models_;
  /// The first model as built: the mesh and its dofs, the same for every model (kept while a cut
  /// model is made whole again).
  std::shared_ptr<const simulation::ScenarioModel> first_;
  std::shared_ptr<const SurfaceView> surface_;
  std::vector<std::vector<int>> neighbours_;  ///< per node, the nodes it shares a tetrahedron with
  Eigen::AlignedBox3d box_;
  double dt_, radius_mm_;
  integrators::HapticNewton newton_;
  std::string loads_said_;
  /// live's surface_unknown and surface_static, for live.display.view.
  void map_surface(LiveModel& live) const;
  /// The vertices' flags (fixed, each model's ROI).
  void flag_vertices(SurfaceView& view) const;
};

}  // namespace roifem::serve
