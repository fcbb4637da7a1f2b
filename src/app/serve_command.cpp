// SPDX-License-Identifier: GPL-3.0-or-later
// roifem serve SCENARIO.toml [--port P] [--host H]: the browser simulator (src/serve, web/).
#include <iostream>
#include <optional>

#include "app/commands.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "scenario/scenario.hpp"
#include "serve/asset_files.hpp"
#include "serve/live_scene.hpp"
#include "serve/physics_loop.hpp"
#include "serve/request_guard.hpp"
#include "serve/server.hpp"
#include "solvers/blas_threads.hpp"

namespace roifem::app {

namespace {

/// What the command line gives, over the scenario's [haptic] table, over the defaults.
struct HapticChoice {
  std::optional<double> rate_hz;
  std::optional<int> newton_iterations;
  double newton_tolerance = 0;
};

void serve(const std::string& scenario_file, const serve::ServeOptions& options, const HapticChoice& haptic, double radius_mm,
           const std::vector<std::string>& models, const serve::PhysicsSettings& hand, serve::SceneLoads loads) {
  serve::check_listen_address(options.host);  // before the models' minutes of preparation
  if (!serve::is_loopback_address(options.host))
    std::cerr << "roifem serve: warning: listening on " << options.host
              << ", not the loopback address: anyone who reaches this machine can open the page and steer the model\n";
  const scenario::Scenario scenario = scenario::read_scenario(scenario_file);
  const serve::HapticSettings settings =
      serve::haptic_settings(scenario, haptic.rate_hz, haptic.newton_iterations, haptic.newton_tolerance);
  // One BLAS thread: the physics thread takes a core, and OpenBLAS's threads spinning beside it
  // would slow every other solve, a recovery of the static part a hundredfold (docs/design-figures.md).
  const solvers::BlasThreadsScope blas(1);
  if (!options.record.empty()) check_output_directory(options.record);
  std::cout << "roifem serve: preparing the models of " << scenario_file << "\n" << std::flush;
  serve::LiveScene scene(scenario, settings.rate_hz, radius_mm, models, std::cout, settings.newton, loads);
  serve::PhysicsLoop physics(scene, hand);
  serve::Server server(scene, physics, serve::AssetFiles({{"/", serve::page_directory()}, {"/three/", serve::three_directory()}}),
                       options, std::cout);
  std::cout << "roifem serve: open http://"
            << (options.host.find(':') != std::string::npos ? "[" + options.host + "]" : options.host) << ":" << server.port()
            << "/ in a browser (the haptic loop at " << settings.rate_hz << " Hz; Ctrl-C stops)\n"
            << std::flush;
  if (const int signal = server.run(); signal != 0)
    throw Interrupted(signal, "serve stopped by signal " + std::to_string(signal) + ": every client closed, every grab kept");
}

}  // namespace

void add_serve_command(CLI::App& app, Action& action) {
  struct Options {
    std::string scenario;
    serve::ServeOptions serve;
    std::string record;
    HapticChoice haptic;
    double radius_mm = 5;
    std::vector<std::string> models;
    serve::PhysicsSettings hand;
    bool loads = false;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "serve",
      "Serve a page on which you steer the scenario's brain live: drag a tool on its surface, see it deform and read the "
      "force, at the haptic rate, and switch between the full model and the condensed ROI (static, Guyan, Craig-Bampton), "
      "linear or at large deformation (neo-Hookean: the whole brain, or the hybrid ROI). "
      "The scenario's own tools and cuts are left out, and its loads unless --loads; every grab starts from rest and can "
      "be saved for `roifem run` to replay (--record). Nothing is fetched from outside: three.js is Debian's libjs-three");
  cmd->add_option("SCENARIO", o->scenario, "Scenario file (.toml): mesh, material, supports, loads, ROI")->required();
  cmd->add_option("--port", o->serve.port, "TCP port (0: any free one; the line 'open http://...' says which)")
      ->capture_default_str();
  cmd->add_option("--host", o->serve.host,
                  "Address to listen on: the loopback address unless you give another (then anyone who reaches the "
                  "machine can steer it: a warning says so)")
      ->capture_default_str();
  cmd->add_option("--models", o->models,
                  "The models to prepare and switch between. Linear: full, static, guyan, craig-bampton-K. Large deformation: "
                  "full-neo-hookean (the whole brain neo-Hookean) and static-neo-hookean (the hybrid ROI: the ROI's elements "
                  "neo-Hookean over the linear condensed remainder), with the scenario's moduli as the law's small-strain "
                  "moduli. Cut by the page's scalpel: full-cut and static-cut (a copy of full or static that the strokes "
                  "cut; the others stay whole). Default: full and, with an [roi], static, guyan, craig-bampton-10, "
                  "static-cut and static-neo-hookean (a neo-Hookean scenario's full-neo-hookean and static-neo-hookean "
                  "first; without an [roi], full-cut); on a large brain Guyan's and Craig-Bampton's preparation takes "
                  "minutes");
  cmd->add_option("--rate-hz", o->haptic.rate_hz,
                  "The haptic loop's rate, one trapezoidal step per tick (default: the scenario's [haptic] rate_hz, else 1000)");
  cmd->add_option("--tool-radius-mm", o->radius_mm,
                  "The tool's footprint: the boundary nodes within this radius of the picked point")
      ->capture_default_str();
  cmd->add_option("--hand-speed-mm-s", o->hand.hand_speed_mm_s, "The tool's fastest motion towards the mouse")
      ->capture_default_str();
  cmd->add_option("--reach-mm", o->hand.reach_mm, "The farthest the tool goes from where it picked")->capture_default_str();
  cmd->add_option("--newton-iterations", o->haptic.newton_iterations,
                  "A neo-Hookean model's modified-Newton iterations per tick, on the linear factor (a fixed budget: the page "
                  "shows the residual it leaves; default: the scenario's [haptic] newton_iterations, else 2)");
  cmd->add_option("--newton-tolerance", o->haptic.newton_tolerance,
                  "Stop a tick's iterations earlier, once the residual is within this share of the law's correction (0: "
                  "never; e.g. 1e-12 with --newton-iterations 200 converges every tick, as roifem run's replay does)")
      ->capture_default_str();
  cmd->add_flag("--loads", o->loads,
                "Keep the scenario's [[load]]s, ramping from each grab's start as in `roifem run` (default: left out, the "
                "hand alone on the unloaded brain; the page says which)");
  cmd->add_option("--record", o->record,
                  "Write every grab to DIR (grab-NNN-K.csv, its path; -force.csv, the live force; .toml, the scenario "
                  "`roifem run` replays it with)");
  cmd->callback([&action, o] {
    action = [o] {
      o->serve.record = o->record;
      serve(o->scenario, o->serve, o->haptic, o->radius_mm, o->models, o->hand,
            o->loads ? serve::SceneLoads::kept : serve::SceneLoads::left_out);
    };
  });
}

}  // namespace roifem::app
