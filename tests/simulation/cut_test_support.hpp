// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the cut tests share: the bar's material, a scenario from text, and the comparison of a cut
// model with the model assembled (and condensed) from scratch on the cut mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <random>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "condensation/reduced_model.hpp"
#include "integrators/trapezoid.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/msh_writer.hpp"
#include "model/fem_model.hpp"
#include "scenario/scenario.hpp"
#include "simulation/scenario_stepper.hpp"
#include "test_support.hpp"

namespace roifem::simulation::cut_test {

inline constexpr const char* kMaterial = R"(
[material]
young_Pa = 3000.0
poisson = 0.45
rho_kg_m3 = 1000.0
alpha_per_s = 2.0
)";

inline constexpr double g = 9.81;
/// The hanging bar's alpha (none) and its gravity.
inline constexpr const char* kGravity = "0.0\n[[load]]\ngravity_m_s2 = [0.0, 0.0, -9.81]\n";

/// A scenario on `mesh_file` from the text after its mesh line.
inline scenario::Scenario scenario_on(const std::filesystem::path& mesh_file, const std::string& text) {
  return scenario::parse_scenario("mesh = \"" + mesh_file.string() + "\"\n" + text, "cut.toml", mesh_file.parent_path());
}

/// A 10 x 10 x 40 mm bar hanging from its top (z = 40 mm), cut through the layer z in [15, 20] mm
/// by a blade crossing it along y at `start` (within a microsecond: in one step), in `mode`.
inline std::string hanging_bar(const std::string& integrator, double dt, long steps, double start, const std::string& rest,
                               const std::string& mode = "remove") {
  return std::string(R"(
[material]
young_Pa = 3000.0
poisson = 0.45
rho_kg_m3 = 1000.0
alpha_per_s = )") +
         rest + R"(
[boundary]
fixed = ["z1"]
[[cut]]
mode = ")" +
         mode + R"("
edge_from_mm = [-1.0, -1.0, 17.5]
edge_to_mm = [11.0, -1.0, 17.5]
move_mm = [0.0, 12.0, 0.0]
start_s = )" +
         std::to_string(start) + R"(
duration_s = 0.000001
[time]
integrator = ")" +
         integrator + "\"\ndt_s = " + std::to_string(dt) + "\nsteps = " + std::to_string(steps) + "\n";
}

/// The bar's support and loads: held at x = 0, pulled down by 0.5 mN at x = 30 mm (ramped over
/// 0.05 s), under gravity.
inline constexpr const char* kBarHeldAndLoaded = R"(
[boundary]
fixed = ["x0"]
[[load]]
set = "x1"
force_N = [0.0, 0.0, -0.0005]
ramp_s = 0.05
[[load]]
gravity_m_s2 = [0.0, 0.0, -9.81]
)";

/// The bar of the exactness tests: 30 x 10 x 10 mm, 6 x 2 x 2 cells, held at x = 0, pulled down at
/// x = 30 mm, under gravity; two blades in `mode`: one from the top to 3 mm above the bottom through
/// the middle, one through the top layer at x = end_mm (at 27.5 mm in remove mode it leaves the far
/// end's three top nodes with no tetrahedron, one of them loaded).
inline std::string bar_scenario(const std::string& roi, const std::string& mode = "remove", double end_mm = 27.5) {
  const std::string end = std::to_string(end_mm);
  return std::string(kMaterial) + kBarHeldAndLoaded + R"(
[[cut]]
name = "middle"
mode = ")" +
         mode + R"("
edge_from_mm = [17.5, -1.0, 11.0]
edge_to_mm = [17.5, 11.0, 11.0]
move_mm = [0.0, 0.0, -8.0]
start_s = 0.02
duration_s = 0.05
[[cut]]
name = "end"
mode = ")" +
         mode + R"("
edge_from_mm = [)" +
         end + R"(, -1.0, 11.0]
edge_to_mm = [)" +
         end + R"(, 11.0, 11.0]
move_mm = [0.0, 0.0, -5.0]
start_s = 0.04
duration_s = 0.02
)" + roi +
         R"(
[time]
integrator = "trapezoid"
dt_s = 0.005
steps = 40
)";
}

/// A model the rebuild tests run: the full model, or the bar's far half condensed (a ball of
/// `radius_mm` around x = 22.5 mm) by static condensation or Guyan's reduction.
struct ModelCase {
  std::string name, roi;
};

inline std::vector<ModelCase> model_cases(double radius_mm) {
  const std::string ball =
      "[roi]\nkind = \"ball\"\ncenter_mm = [22.5, 5.0, 5.0]\nradius_mm = " + std::to_string(radius_mm) + "\n";
  return {{"full", ""}, {"static", ball}, {"guyan", ball + "reduction = \"guyan\"\n"}};
}

/// The bar of the exactness tests (30 x 10 x 10 mm, 6 x 2 x 2 cells) written as DIR/bar.msh: its path.
inline std::filesystem::path write_bar(const test::TempDir& dir) {
  mesh::write_msh(mesh::structured_box_mesh(6, 2, 2, 0.03, 0.01, 0.01), dir / "bar.msh", mm);
  return dir / "bar.msh";
}

/// Expects `text` (a scenario on the bar's mesh) with `old_text` replaced by `new_text` to be
/// refused, with a message matching `pattern`.
inline void expect_refused(std::string text, const std::string& old_text, const std::string& new_text,
                           const std::string& pattern) {
  test::TempDir dir;
  const std::filesystem::path bar = write_bar(dir);
  if (!old_text.empty()) {
    ASSERT_NE(text.find(old_text), std::string::npos) << old_text;
    text.replace(text.find(old_text), old_text.size(), new_text);
  }
  try {
    ScenarioStepper stepper(scenario_on(bar, text));
    FAIL() << "not refused: " << pattern;
  } catch (const InputError& e) {
    EXPECT_TRUE(std::regex_search(e.what(), std::regex(pattern))) << e.what();
  }
}

/// (node, component) per unknown of a full model, or of its reduction.
inline std::vector<std::pair<int, int>> unknowns(const model::FemModel& f, const condensation::ReducedModel* r) {
  std::vector<std::pair<int, int>> out;
  const std::vector<Index>& free = r ? r->partition().d : std::vector<Index>{};
  const Index n = r ? static_cast<Index>(free.size()) : f.dofs->num_free();
  for (Index i = 0; i < n; ++i) {
    const Index full = f.dofs->full_dof(r ? free[static_cast<std::size_t>(i)] : i);
    out.emplace_back(static_cast<int>(full / 3), static_cast<int>(full % 3));
  }
  return out;
}

/// A system rebuilt from scratch beside the cut one: per unknown of the rebuilt, the cut's.
struct Rebuilt {
  const model::SecondOrderSystem& expected;
  const model::SecondOrderSystem& system;
  std::vector<Index> at;

  Rebuilt(const model::SecondOrderSystem& rebuilt, const std::vector<std::pair<int, int>>& rebuilt_unknowns,
          const model::SecondOrderSystem& cut, const std::vector<std::pair<int, int>>& cut_unknowns)
      : expected(rebuilt), system(cut) {
    std::map<std::pair<int, int>, Index> where;
    for (std::size_t i = 0; i < cut_unknowns.size(); ++i) where[cut_unknowns[i]] = static_cast<Index>(i);
    for (const auto& u : rebuilt_unknowns) at.push_back(where.at(u));
  }
  /// max |a - b_cut| / max |a| over the rebuilt's unknowns.
  double relative(const Vector& a, const Vector& b_cut) const {
    double gap = 0;
    for (Index i = 0; i < a.size(); ++i) gap = std::max(gap, std::abs(a[i] - b_cut[at[static_cast<std::size_t>(i)]]));
    return gap / a.lpNorm<Eigen::Infinity>();
  }
  struct Gaps {
    double K = 0, M = 0, f = 0;
  };
  /// K x, M x (x random, zero at the cut's other unknowns) and f(t) at two times, relative.
  Gaps operator_gaps() const {
    const Index n = expected.size();
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(-1, 1);
    Vector x(n), x_cut = Vector::Zero(system.size()), y(n), y_cut(system.size());
    for (Index i = 0; i < n; ++i) x_cut[at[static_cast<std::size_t>(i)]] = x[i] = uniform(random);
    Gaps gaps;
    expected.apply_stiffness(x, y);
    system.apply_stiffness(x_cut, y_cut);
    gaps.K = relative(y, y_cut);
    expected.apply_mass(x, y);
    system.apply_mass(x_cut, y_cut);
    gaps.M = relative(y, y_cut);
    for (const double t : {0.01, 0.2}) gaps.f = std::max(gaps.f, relative(expected.load.at(t), system.load.at(t)));
    return gaps;
  }
  /// The cut model's run `steps` further against a fresh trapezoidal rule on the rebuilt model from
  /// the same state: max |u - u_rebuilt| / max |u_rebuilt|.
  double trajectory_gap(ScenarioStepper& stepper, double dt, int steps) const {
    const Index n = expected.size();
    model::State mirror = model::State::at_rest(n, stepper.state().t);
    for (Index i = 0; i < n; ++i) {
      mirror.u[i] = stepper.state().u[at[static_cast<std::size_t>(i)]];
      mirror.v[i] = stepper.state().v[at[static_cast<std::size_t>(i)]];
    }
    integrators::Trapezoid fresh(dt);
    fresh.reset(expected, mirror);
    for (int k = 0; k < steps; ++k) {
      stepper.step();
      fresh.advance_to(stepper.state().t, mirror);
    }
    double peak = 0, gap = 0;
    for (Index i = 0; i < n; ++i) {
      peak = std::max(peak, std::abs(mirror.u[i]));
      gap = std::max(gap, std::abs(mirror.u[i] - stepper.state().u[at[static_cast<std::size_t>(i)]]));
    }
    return gap / peak;
  }
};

}  // namespace roifem::simulation::cut_test
