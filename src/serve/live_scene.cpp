// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/live_scene.hpp"

#include <algorithm>
#include <optional>
#include <ostream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/timer.hpp"
#include "condensation/reduced_model.hpp"
#include "mesh/tet_mesh.hpp"

namespace roifem::serve {

namespace {

/// The reductions the page switches between: each one whose basis does not learn from the loads.
std::vector<condensation::Reduction> live_reductions(const scenario::Scenario& scenario) {
  std::vector<condensation::Reduction> reductions;
  for (const auto& info : condensation::reduction_table()) {
    if (info.learns_from_loads) continue;
    condensation::Reduction r;
    r.kind = &info;
    if (info.counted) {  // the scenario's count where it names this reduction, else 10 modes
      const bool named = scenario.reduction.kind == &info;
      r.modes = named ? scenario.reduction.modes : 10;
      r.cutoff_rad_s = named ? scenario.reduction.cutoff_rad_s : 0;
    }
    reductions.push_back(r);
  }
  return reductions;
}

SurfaceView surface_of(const mesh::TetMesh& mesh) {
  SurfaceView view;
  view.nodes = mesh::boundary_nodes(mesh);
  std::vector<int> vertex(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (std::size_t k = 0; k < view.nodes.size(); ++k) vertex[static_cast<std::size_t>(view.nodes[k])] = static_cast<int>(k);
  for (const mesh::Triangle& f : mesh::boundary_faces(mesh))
    view.triangles.push_back(
        {vertex[static_cast<std::size_t>(f[0])], vertex[static_cast<std::size_t>(f[1])], vertex[static_cast<std::size_t>(f[2])]});
  view.flags.assign(view.nodes.size(), 0);
  return view;
}

std::vector<std::vector<int>> node_neighbours(const mesh::TetMesh& mesh) {
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(mesh.num_nodes()));
  for (const auto& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (a != b) neighbours[static_cast<std::size_t>(t[a])].push_back(t[b]);
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

}  // namespace

std::pair<const ModelKindInfo*, std::string> kind_of_name(std::string_view name) {
  for (const ModelKindInfo& k : model_kinds)
    if (!k.suffix.empty() && name.size() > k.suffix.size() && name.ends_with(k.suffix))
      return {&k, std::string(name.substr(0, name.size() - k.suffix.size()))};
  return {&model_kind(ModelKind::linear), std::string(name)};
}

std::string model_name(std::string_view base, ModelKind kind) { return std::string(base) + std::string(model_kind(kind).suffix); }

namespace {

/// A model to prepare: its name, its reduction (none: the full model) and its law.
struct PlannedModel {
  std::string name;
  std::optional<condensation::Reduction> reduction;
  fem::MaterialModel law = fem::MaterialModel::linear;
  bool cut = false;  ///< the page's scalpel cuts it
};

bool is_neo_hookean(const scenario::Scenario& scenario) {
  if (scenario.material.model != fem::MaterialModel::linear) return true;
  return std::any_of(scenario.material_regions.begin(), scenario.material_regions.end(),
                     [](const fem::RegionMaterial& r) { return r.material.model != fem::MaterialModel::linear; });
}

/// The models to prepare: those named, or by default the linear ones and the hybrid ROI (a
/// neo-Hookean scenario's own law first).
std::vector<PlannedModel> model_plan(const scenario::Scenario& scenario, const std::vector<std::string>& names) {
  const auto planned = [](std::string_view base, std::optional<condensation::Reduction> r, ModelKind kind) {
    const ModelKindInfo& k = model_kind(kind);
    return PlannedModel{model_name(base, kind), r, k.law, k.cut};
  };
  std::vector<PlannedModel> plan;
  if (names.empty()) {
    const condensation::Reduction static_condensation;
    std::vector<PlannedModel> linear_models{planned("full", std::nullopt, ModelKind::linear)};
    if (scenario.roi)
      for (const auto& r : live_reductions(scenario)) linear_models.push_back(planned(r.label(), r, ModelKind::linear));
    if (scenario.roi)
      linear_models.push_back(planned(static_condensation.label(), static_condensation, ModelKind::cut));
    else
      linear_models.push_back(planned("full", std::nullopt, ModelKind::cut));
    const PlannedModel hybrid = planned(static_condensation.label(), static_condensation, ModelKind::neo_hookean);
    if (!is_neo_hookean(scenario)) {  // the linear models, then the hybrid ROI
      plan = linear_models;
      if (scenario.roi) plan.push_back(hybrid);
      return plan;
    }
    plan.push_back(planned("full", std::nullopt, ModelKind::neo_hookean));  // the scenario's own law first
    if (scenario.roi) plan.push_back(hybrid);
    plan.insert(plan.end(), linear_models.begin(), linear_models.end());
    return plan;
  }
  const std::string cut_suffix(model_kind(ModelKind::cut).suffix);
  const std::string neo_suffix(model_kind(ModelKind::neo_hookean).suffix);
  for (const std::string& name : names) {
    const auto [kind, base] = kind_of_name(name);
    if (kind->cut && base != "full" && base != condensation::Reduction{}.label())
      throw InputError(format(
          "serve: --models: %s: the page's scalpel cuts the linear full model (full%s) or static condensation (static%s): %s",
          name.c_str(), cut_suffix.c_str(), cut_suffix.c_str(),
          kind_of_name(base).first->law != fem::MaterialModel::linear
              ? "cuts are built for the linear material"
              : "a reduction by modes keeps the uncut mesh's modes, and the haptic loop takes a cut on a lumped mass"));
    const bool neo = kind->law != fem::MaterialModel::linear;
    if (base == "full") {
      plan.push_back(planned("full", std::nullopt, kind->kind));
      continue;
    }
    condensation::Reduction r;
    try {
      r = condensation::parse_reduction(base);
    } catch (const InputError& e) {
      throw InputError(format("serve: --models: '%s' is neither full nor a reduction (either with %s or not): %s", name.c_str(),
                              neo_suffix.c_str(), e.what()));
    }
    if (r.info().learns_from_loads)
      throw InputError("serve: --models: " + name + " learns its basis from the scenario's loads, not from a hand");
    if (!scenario.roi)
      throw InputError("serve: --models: " + name + " reduces an ROI, and " + scenario.file.string() + " has no [roi]");
    if (neo && !r.is_static_condensation())
      throw InputError(
          format("serve: --models: %s: a reduction by modes linearizes the ROI's motion; the neo-Hookean "
                 "ROI takes static condensation (static%s)",
                 name.c_str(), neo_suffix.c_str()));
    plan.push_back(planned(r.label(), r, kind->kind));
  }
  return plan;
}

/// `scenario` with `law` on every material.
scenario::Scenario with_law(scenario::Scenario scenario, fem::MaterialModel law) {
  scenario.material.model = law;
  for (fem::RegionMaterial& r : scenario.material_regions) r.material.model = law;
  return scenario;
}

}  // namespace

LiveScene::LiveScene(const scenario::Scenario& scenario, double rate_hz, double radius_mm, const std::vector<std::string>& models,
                     std::ostream& log, integrators::HapticNewton newton, SceneLoads loads)
    : scenario_(scenario), dt_(1.0 / rate_hz), radius_mm_(radius_mm), newton_(newton) {
  if (!(rate_hz > 0) || !(rate_hz <= 100000))
    throw InputError(format("serve: a haptic rate of %g Hz (0 < rate <= 100 kHz)", rate_hz));
  if (!(radius_mm > 0)) throw InputError(format("serve: a tool radius of %g mm (it must be positive)", radius_mm));
  if (newton.iterations < 1 || newton.iterations > 1000 || !(newton.tolerance >= 0))
    throw InputError(format("serve: %d Newton iterations a tick within %g (1 to 1,000 iterations, a tolerance >= 0)",
                            newton.iterations, newton.tolerance));
  if (scenario.element != fem::Element::tet4) throw InputError(scenario.file.string() + ": serve takes tet4 elements only");
  const auto ogden = [](const fem::Material& m) { return m.model == fem::MaterialModel::ogden; };
  if (ogden(scenario.material) || std::any_of(scenario.material_regions.begin(), scenario.material_regions.end(),
                                              [&](const fem::RegionMaterial& r) { return ogden(r.material); }))
    throw InputError(scenario.file.string() +
                     ": serve's models are linear and neo-Hookean, and this scenario's [material] is Ogden; `roifem run` "
                     "runs it");
  if (!scenario_.tools.empty() || !scenario_.cuts.empty())
    log << "serve: the scenario's " << scenario_.tools.size() << " [[tool]](s) and " << scenario_.cuts.size()
        << " [[cut]](s) are left out: the page's hand is the tool\n";
  if (scenario_.restart) log << "serve: the scenario's [restart] is left out: every grab starts from rest\n";
  scenario_.tools.clear();
  scenario_.cuts.clear();
  scenario_.restart.reset();
  const std::size_t given = scenario_.loads.size();
  if (loads == SceneLoads::left_out) scenario_.loads.clear();
  loads_said_ = given == 0 ? "none (the scenario has no [[load]])"
                : loads == SceneLoads::kept
                    ? format("the scenario's %zu [[load]](s), ramping from each grab's start (--loads)", given)
                    : format("none: the scenario's %zu [[load]](s) left out, the hand alone (--loads keeps them)", given);
  log << "serve: loads: " << loads_said_ << "\n";
  for (const auto& [name, reduction, law, cut] : model_plan(scenario_, models)) {
    const Stopwatch clock;
    scenario::Scenario variant = with_law(scenario_, law);
    if (!reduction) variant.roi.reset();
    if (reduction) variant.reduction = *reduction;
    LiveModel live;
    live.name = name;
    live.law = law;
    live.physics.model = simulation::build_scenario_model(variant);
    live.display.model = live.physics.model;
    live.unknowns = live.physics.model->system().size();
    live.roi_size = live.physics.model->condensation ? live.physics.model->roi_nodes.size() : 0;
    if (reduction) {
      live.reduction = *reduction;
      live.description = live.nonlinear()
                             ? "the hybrid ROI: the ROI's elements neo-Hookean over the linear static part, condensed"
                             : std::string(reduction->info().description);
    } else {
      live.description = live.nonlinear() ? "the full dynamic model of the whole brain, neo-Hookean"
                                          : "the full dynamic model of the whole brain";
    }
    live.built_from = variant;
    live.cut_model = cut;
    if (cut) {
      live.physics.cuts = std::make_unique<simulation::ElementCuts>(variant, *live.physics.model);
      live.physics.on_cut.assign(static_cast<std::size_t>(live.physics.model->mesh.num_nodes()), 0);
      live.description += ", cut by the page's scalpel";
    }
    live.physics.haptic = std::make_unique<integrators::HapticTrapezoid>(
        live.physics.model->system(), dt_, live.nonlinear() ? newton_ : integrators::HapticNewton{});
    const auto& mesh = live.physics.model->mesh;
    live.in_roi.assign(static_cast<std::size_t>(mesh.num_nodes()), 0);
    const fem::DofMap& dofs = *live.physics.model->full.dofs;
    if (live.condensed())
      for (const int n : live.physics.model->roi_nodes) live.in_roi[static_cast<std::size_t>(n)] = 1;
    else
      for (Index n = 0; n < mesh.num_nodes(); ++n) live.in_roi[static_cast<std::size_t>(n)] = dofs.free_dof(n, 0) >= 0 ? 1 : 0;
    log << format("serve: model %-18s %7ld unknowns, prepared in %.2f s\n", name.c_str(),
                  static_cast<long>(live.physics.model->system().size()), clock.seconds())
        << std::flush;
    models_.push_back(std::move(live));
  }
  first_ = models_.front().physics.model;
  const mesh::TetMesh& m = mesh();
  auto surface = std::make_shared<SurfaceView>(surface_of(m));
  flag_vertices(*surface);
  surface_ = std::move(surface);
  neighbours_ = node_neighbours(m);
  for (Index n = 0; n < m.num_nodes(); ++n) box_.extend(m.node(static_cast<int>(n)));
  for (LiveModel& live : models_) {
    live.display.view = surface_;
    if (live.cuttable()) live.display.shown_tets.assign(m.tets.size(), true);
    map_surface(live);
  }
}

void LiveScene::flag_vertices(SurfaceView& view) const {
  const fem::DofMap& dofs = *first_->full.dofs;
  for (std::size_t v = 0; v < view.nodes.size(); ++v) {
    const int n = view.nodes[v];
    if (dofs.free_dof(n, 0) < 0 || dofs.free_dof(n, 1) < 0 || dofs.free_dof(n, 2) < 0) view.flags[v] |= 1;
    for (std::size_t k = 0; k < models_.size() && k < 7; ++k)
      if (models_[k].in_roi[static_cast<std::size_t>(n)]) view.flags[v] |= static_cast<std::uint8_t>(2u << k);
  }
}

std::shared_ptr<simulation::ScenarioModel> LiveScene::make_whole(std::size_t k) {
  LiveModel& live = models_.at(k);
  if (!live.cuttable()) throw Error("internal: serve: " + live.name + " is not a cut model");
  std::shared_ptr<simulation::ScenarioModel> fresh = simulation::build_scenario_model(live.built_from);
  live.physics.cuts = std::make_unique<simulation::ElementCuts>(live.built_from, *fresh);
  live.physics.haptic = std::make_unique<integrators::HapticTrapezoid>(fresh->system(), dt_);
  live.physics.on_cut.assign(live.physics.on_cut.size(), 0);
  live.physics.haptic_stale = false;
  live.physics.model = fresh;
  return fresh;
}

void LiveScene::show_whole(std::size_t k, std::shared_ptr<simulation::ScenarioModel> fresh) {
  LiveModel& live = models_.at(k);
  live.display.model = std::move(fresh);
  live.display.shown_tets.assign(live.display.shown_tets.size(), true);
  live.display.view = surface_;
  map_surface(live);
}

void LiveScene::cut_surface(std::size_t k, const std::vector<Index>& removed) {
  LiveModel& live = models_.at(k);
  if (!live.cuttable()) throw Error("internal: serve: the display cut the uncut model " + live.name);
  for (const Index e : removed) live.display.shown_tets.at(static_cast<std::size_t>(e)) = false;
  mesh::TetMesh left;
  left.nodes = mesh().nodes;
  for (std::size_t e = 0; e < live.display.shown_tets.size(); ++e)
    if (live.display.shown_tets[e]) left.tets.push_back(mesh().tets[e]);
  auto view = std::make_shared<SurfaceView>(surface_of(left));
  flag_vertices(*view);
  live.display.view = std::move(view);
  map_surface(live);
}

HapticSettings haptic_settings(const scenario::Scenario& scenario, std::optional<double> rate_hz,
                               std::optional<int> newton_iterations, double newton_tolerance) {
  HapticSettings settings;
  settings.rate_hz = rate_hz.value_or(scenario.haptic_rate_hz.value_or(settings.rate_hz));
  settings.newton.iterations = newton_iterations.value_or(scenario.haptic_newton_iterations.value_or(settings.newton.iterations));
  settings.newton.tolerance = newton_tolerance;
  return settings;
}

std::optional<std::size_t> LiveScene::reference_of(std::size_t k) const {
  const LiveModel& live = models_.at(k);
  if (!live.condensed() || live.cuttable()) return std::nullopt;
  for (std::size_t j = 0; j < models_.size(); ++j)
    if (!models_[j].condensed() && !models_[j].cuttable() && models_[j].law == live.law) return j;
  return std::nullopt;
}

LiveCutResult LiveModel::cut(const std::vector<Index>& crossed, model::State* grab, const std::vector<int>& hand) {
  LiveCutResult result;
  if (!cuttable()) {
    result.why_not = format("the %s model is not cut by the scalpel (choose a model whose name ends in %s)", name.c_str(),
                            std::string(model_kind(ModelKind::cut).suffix).c_str());
    result.refused = true;
    return result;
  }
  const std::vector<bool>& there = physics.cuts->still_there();
  std::vector<Index> elements;
  for (const Index e : crossed)
    if (there[static_cast<std::size_t>(e)]) elements.push_back(e);
  if (elements.empty()) {
    result.why_not = crossed.empty() ? std::string("the stroke's blade crosses no tetrahedron")
                                     : format("the %zu tetrahedra the stroke crosses are already removed", crossed.size());
    return result;
  }
  const mesh::TetMesh& mesh = physics.model->mesh;
  for (const Index e : elements)
    if (const auto why = physics.cuts->refusal_to_remove(mesh, e, hand)) {
      result.why_not = "it reaches tetrahedron " + std::to_string(e) + ", " + *why;
      result.refused = true;
      return result;
    }
  if (const auto why = physics.cuts->refusal_to_empty(mesh, elements.size(), condensed())) {
    result.why_not = "it " + *why;
    result.refused = true;
    return result;
  }
  model::State at_rest = grab ? model::State{} : model::State::at_rest(physics.model->system().size());
  model::State& state = grab ? *grab : at_rest;
  try {
    result.taken = physics.cuts->remove(elements, *physics.model, state);
  } catch (const Error& e) {  // nothing removed
    result.why_not = e.what();
    result.refused = true;
    return result;
  }
  // Between grabs the next pick factors the cut model afresh; during one the grab goes on with the
  // corrected factor, and the next pick after it factors afresh too (a factor with a correction
  // takes no new hand: HapticTrapezoid::attach).
  physics.haptic_stale = true;
  if (grab) try {
      physics.haptic->take_change(result.taken->change, *grab);
    } catch (const Error& e) {
      result.grab_ended_because = e.what();
    }
  for (const Index e : result.taken->elements)
    for (const int n : mesh.tets[static_cast<std::size_t>(e)]) physics.on_cut[static_cast<std::size_t>(n)] = 1;
  return result;
}

std::size_t LiveScene::default_model() const {
  for (std::size_t k = 0; k < models_.size(); ++k)
    if (models_[k].condensed()) return k;
  return 0;
}

scenario::Scenario LiveScene::scenario_of(std::size_t k) const { return with_law(scenario_, models_.at(k).law); }

std::variant<Grip, std::string> LiveScene::grip(std::size_t k, const Vec3& center_mm) const {
  const LiveModel& live = models_.at(k);
  const mesh::TetMesh& m = mesh();
  Grip grip{.center_mm = center_mm, .nodes = {}, .dofs = {}};
  const Vec3 center = center_mm * mm;  // as the scenario reader reads center_mm
  const double radius = radius_mm_ * mm;
  for (const int n : surface_->nodes)
    if ((m.node(n) - center).norm() <= radius) grip.nodes.push_back(n);
  if (grip.nodes.empty())
    return format("no boundary node within %g mm of (%.1f, %.1f, %.1f) mm", radius_mm_, center_mm.x(), center_mm.y(),
                  center_mm.z());
  const fem::DofMap& dofs = *live.physics.model->full.dofs;
  for (const int n : grip.nodes) {
    if (dofs.free_dof(n, 0) < 0 || dofs.free_dof(n, 1) < 0 || dofs.free_dof(n, 2) < 0)
      return format("node %d there is fixed: a tool moves free nodes only", n);
    if (!live.in_roi[static_cast<std::size_t>(n)])
      return format("node %d there is outside the %s model's ROI", n, live.name.c_str());
    for (const int neighbour : neighbours_[static_cast<std::size_t>(n)])
      if (!live.in_roi[static_cast<std::size_t>(neighbour)] && dofs.free_dof(neighbour, 0) >= 0)
        return format(
            "node %d there shares an element with node %d of the static part: the ROI must hold the tool's nodes "
            "and their neighbours",
            n, neighbour);
  }
  grip.dofs = live.condensed() ? roi::node_dofs_in_reduced(grip.nodes, live.physics.model->condensation->partition(), dofs)
                               : roi::node_dofs_in_full(grip.nodes, dofs);
  return grip;
}

void LiveScene::surface_displacement(std::size_t k, const Vector& u, double t, bool recover_static, std::vector<float>& out_mm) {
  LiveModel& live = models_.at(k);
  if (live.condensed() && recover_static) {
    const Vector u_s = live.display.model->condensation->recover_static(u, t);
    for (std::size_t i = 0; i < live.display.surface_static.size(); ++i)
      if (live.display.surface_static[i] >= 0)
        live.display.static_surface_mm[i] = static_cast<float>(u_s[live.display.surface_static[i]] / mm);
  }
  out_mm.resize(live.display.surface_unknown.size());
  for (std::size_t i = 0; i < out_mm.size(); ++i)
    out_mm[i] = live.display.surface_unknown[i] >= 0 ? static_cast<float>(u[live.display.surface_unknown[i]] / mm)
                                                     : live.display.static_surface_mm[i];
}

void LiveScene::map_surface(LiveModel& live) const {
  const fem::DofMap& dofs = *live.display.model->full.dofs;
  std::vector<Index> unknown(static_cast<std::size_t>(dofs.num_free()), -1), in_static(unknown.size(), -1);
  if (live.condensed()) {
    const roi::Partition& p = live.display.model->condensation->partition();
    for (std::size_t a = 0; a < p.d.size(); ++a) unknown[static_cast<std::size_t>(p.d[a])] = static_cast<Index>(a);
    for (std::size_t a = 0; a < p.s.size(); ++a) in_static[static_cast<std::size_t>(p.s[a])] = static_cast<Index>(a);
  } else {
    for (std::size_t a = 0; a < unknown.size(); ++a) unknown[a] = static_cast<Index>(a);
  }
  const SurfaceView& view = *live.display.view;
  const std::size_t n = 3 * view.nodes.size();
  live.display.surface_unknown.assign(n, -1);
  live.display.surface_static.assign(n, -1);
  live.display.static_surface_mm.assign(n, 0.0F);
  for (std::size_t v = 0; v < view.nodes.size(); ++v)
    for (int c = 0; c < 3; ++c) {
      const int dof = dofs.free_dof(view.nodes[v], c);
      if (dof < 0) continue;
      live.display.surface_unknown[3 * v + static_cast<std::size_t>(c)] = unknown[static_cast<std::size_t>(dof)];
      live.display.surface_static[3 * v + static_cast<std::size_t>(c)] = in_static[static_cast<std::size_t>(dof)];
    }
}

}  // namespace roifem::serve
