// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/hand_recording.hpp"

#include <fstream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "serve/scalpel.hpp"

namespace roifem::serve {

namespace fs = std::filesystem;

namespace {

/// Writes `text` to `path` atomically (InputError naming the file on failure).
void write_file(const fs::path& path, const std::string& text) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temporary_path());
    out << text;
    out.flush();
    if (!out) throw InputError(path.string() + ": could not be written");
  }
  file.commit();
}

std::string path_csv(const GrabRecord& grab) {
  std::string text = "t_s,x_mm,y_mm,z_mm\n";
  for (const HandSample& s : grab.samples)
    text += format("%.17g,%.17g,%.17g,%.17g\n", s.t, s.g.x() / mm, s.g.y() / mm, s.g.z() / mm);
  return text;
}

std::string force_csv(const GrabRecord& grab) {
  std::string text = "t_s,fx_N,fy_N,fz_N\n";
  for (const HandSample& s : grab.samples)
    text += format("%.17g,%.17g,%.17g,%.17g\n", s.t, s.force.x(), s.force.y(), s.force.z());
  return text;
}

scenario::Scenario replay_scenario(const LiveScene& scene, const GrabRecord& grab, const std::string& path_file) {
  const LiveModel& live = scene.models().at(grab.model);
  scenario::Scenario replay = scene.scenario_of(grab.model);
  replay.mesh = fs::absolute(replay.mesh);
  model::SetTool hand;
  hand.name = "hand";
  hand.center = grab.center_mm * mm;
  hand.radius = scene.radius_mm() * mm;
  hand.path.trajectory.emplace();
  hand.path.trajectory_file = path_file;
  replay.tools = {hand};
  replay.cuts.clear();
  const double dt = scene.dt();
  for (const LiveCut& c : grab.cuts)
    replay.cuts.push_back(scalpel_blade("scalpel" + std::to_string(replay.cuts.size() + 1), c.edge_from_mm, c.edge_to_mm,
                                        c.move_mm, c.during ? c.t + dt / 2 : 0.0, dt / 2));
  if (!live.condensed()) {
    replay.roi.reset();
  } else {
    replay.reduction = live.reduction;
    if (replay.roi->kind == roi::RoiSpec::Kind::nearest) replay.roi->count -= static_cast<Index>(grab.grip_nodes);
  }
  replay.integrator = "trapezoid";
  replay.integrator_where.clear();
  replay.rtol.reset();
  replay.atol.reset();
  replay.dt = scene.dt();
  replay.steps = static_cast<long>(grab.samples.size()) - 1;
  replay.field_every = 0;
  return replay;
}

}  // namespace

std::vector<LiveCut> cuts_of_grab(const std::vector<LiveCut>& record, const GrabRecord& grab) {
  std::vector<LiveCut> cuts;
  if (grab.samples.empty()) return cuts;
  for (const LiveCut& c : record) {
    if (c.model != grab.model) continue;
    // Made whole (between grabs, ending the one in progress) before this grab began.
    if (c.whole) {
      if (c.grab < grab.grab) cuts.clear();
      continue;
    }
    if (c.grab < grab.grab || (c.grab == grab.grab && c.during && c.t < grab.samples.back().t)) cuts.push_back(c);
  }
  return cuts;
}

fs::path write_replay(const LiveScene& scene, const GrabRecord& grab, const fs::path& directory, const std::string& name) {
  if (grab.samples.size() < 2 || grab.samples.front().t != 0)
    throw InputError(format("grab %u: nothing to replay (it has %zu ticks from t = 0)", grab.grab,
                            grab.samples.size() > 0 ? grab.samples.size() - 1 : 0));
  const std::string path_file = name + ".csv";
  const scenario::Scenario replay = replay_scenario(scene, grab, path_file);
  write_file(directory / path_file, path_csv(grab));
  write_file(directory / (name + "-force.csv"), force_csv(grab));
  fs::path toml = directory / (name + ".toml");
  const LiveModel& live = scene.models()[grab.model];
  const integrators::HapticNewton& newton = scene.newton();
  const std::string equals =
      !live.nonlinear() ? "to round-off.\n"
      : newton.tolerance > 0
          ? format(
                "to the live loop's Newton tolerance (%g of the law's correction, at most %d iterations a tick;\n# "
                "roifem run solves each step by Newton to convergence).\n",
                newton.tolerance, newton.iterations)
          : format(
                "within what the live loop's fixed budget of %d Newton iterations a tick left unresolved\n# (roifem "
                "run solves each step by Newton to convergence; roifem serve --newton-tolerance converges live).\n",
                newton.iterations);
  write_file(toml, "# A grab on roifem serve's page (" + live.name + " model), replayed by:\n#   roifem run " +
                       toml.filename().string() + " --out DIR\n# Its tools/hand/force_N equals " + name +
                       "-force.csv (the live loop's force) " + equals + replay.resolved_toml());
  return toml;
}

}  // namespace roifem::serve
