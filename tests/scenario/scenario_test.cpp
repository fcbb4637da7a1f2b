// SPDX-License-Identifier: GPL-3.0-or-later
#include "scenario/scenario.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"

namespace roifem::scenario {
namespace {

const std::string valid = R"(
mesh = "brain.msh"
[material]
young_Pa = 3000.0
poisson = 0.45
rho_kg_m3 = 1040
alpha_per_s = 2.5
[boundary]
fixed = ["base"]
[[load]]
set = "opening_left"
force_N = [-0.01, 0, 0]
ramp_s = 0.5
[roi]
kind = "ball"
center_mm = [0, 0, 40]
radius_mm = 25
[time]
dt_s = 0.01
steps = 30
[output]
field_every = 5
)";

std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "s.toml", "/data");
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(ScenarioReader, ReadsEveryKeyWithUnits) {
  const Scenario s = parse_scenario(valid, "s.toml", "/data");
  EXPECT_EQ(s.mesh, std::filesystem::path("/data/brain.msh"));
  EXPECT_NEAR(s.material.young(), 3000, 1e-9);
  EXPECT_NEAR(s.material.poisson(), 0.45, 1e-12);
  EXPECT_EQ(s.material.rho, 1040);
  EXPECT_EQ(s.material.alpha, 2.5);
  ASSERT_EQ(s.loads.size(), 1u);
  EXPECT_EQ(s.loads[0].force, Vec3(-0.01, 0, 0));
  EXPECT_EQ(s.loads[0].ramp.duration, 0.5);
  ASSERT_TRUE(s.roi.has_value());
  EXPECT_EQ(s.roi->kind, roi::RoiSpec::Kind::ball);
  EXPECT_NEAR(s.roi->radius, 0.025, 1e-15);
  EXPECT_NEAR(s.roi->center.z(), 0.040, 1e-15);
  EXPECT_EQ(s.dt, 0.01);
  EXPECT_EQ(s.steps, 30);
  EXPECT_EQ(s.field_every, 5);
}

TEST(ScenarioReader, ResolvedTomlReadsBackToTheSameScenario) {
  const Scenario s = parse_scenario(valid, "s.toml", "/data");
  const Scenario again = parse_scenario(s.resolved_toml(), "resolved.toml", "/elsewhere");
  EXPECT_EQ(again.mesh, s.mesh);
  EXPECT_DOUBLE_EQ(again.material.lambda, s.material.lambda);
  EXPECT_DOUBLE_EQ(again.material.mu, s.material.mu);
  EXPECT_EQ(again.loads[0].force, s.loads[0].force);
  EXPECT_EQ(again.roi->radius, s.roi->radius);
  EXPECT_EQ(again.steps, s.steps);
}

TEST(ScenarioReader, ResolvedTomlKeepsEachCutsMode) {
  // results.h5 records the resolved scenario: an incision read back as a removal would cut another run
  for (const std::string mode : {"remove", "split"}) {
    const Scenario s = parse_scenario(valid + "[[cut]]\nmode = \"" + mode +
                                          "\"\nedge_from_mm = [0, -4, 70]\nedge_to_mm = [0, 4, 70]\nmove_mm = [0, 0, -20]\n"
                                          "duration_s = 1.0\n",
                                      "s.toml", "/data");
    const Scenario again = parse_scenario(s.resolved_toml(), "resolved.toml", "/data");
    ASSERT_EQ(again.cuts.size(), 1U);
    EXPECT_EQ(again.cuts[0].mode, mode == "split" ? cutting::CutMode::split : cutting::CutMode::remove) << mode;
    EXPECT_EQ(again.cuts[0].edge_b, s.cuts[0].edge_b);
    EXPECT_EQ(again.cuts[0].path.displacement, s.cuts[0].path.displacement);
  }
}

TEST(ScenarioReader, ReadsTheHapticTableAndRefusesARateOrBudgetOutOfRange) {
  const Scenario plain = parse_scenario(valid, "s.toml", "/data");
  EXPECT_FALSE(plain.haptic_rate_hz);
  EXPECT_EQ(plain.resolved_toml().find("[haptic]"), std::string::npos);  // as before: no table given, none written
  const Scenario s = parse_scenario(valid + "[haptic]\nrate_hz = 500\nnewton_iterations = 3\n", "s.toml", "/data");
  EXPECT_EQ(s.haptic_rate_hz, std::optional<double>(500));
  EXPECT_EQ(s.haptic_newton_iterations, std::optional<int>(3));
  const Scenario again = parse_scenario(s.resolved_toml(), "resolved.toml", "/data");
  EXPECT_EQ(again.haptic_rate_hz, s.haptic_rate_hz);
  EXPECT_EQ(again.haptic_newton_iterations, s.haptic_newton_iterations);
  EXPECT_EQ(error_of(valid + "[haptic]\nrate_hz = 0\n"), "s.toml: key 'haptic.rate_hz' must lie in (0, 100000] (got 0)");
  EXPECT_EQ(error_of(valid + "[haptic]\nnewton_iterations = 0\n"),
            "s.toml: key 'haptic.newton_iterations' must lie in [1, 1000] (got 0)");
  EXPECT_NE(error_of(valid + "[haptic]\nrate = 500\n").find("did you mean 'rate_hz'"), std::string::npos)
      << error_of(valid + "[haptic]\nrate = 500\n");
}

TEST(ScenarioReader, ReadsTheRestartTableAndLeavesItOutOfTheResolvedScenario) {
  const Scenario plain = parse_scenario(valid, "s.toml", "/data");
  EXPECT_FALSE(plain.restart);
  EXPECT_EQ(plain.restart_interval(), 10 * plain.field_every);  // every 10th field unless given
  const Scenario s = parse_scenario(valid + "[restart]\nfrom = \"run/results.h5\"\nstep = 20\n", "s.toml", "/data");
  ASSERT_TRUE(s.restart);
  EXPECT_EQ(s.restart->from, std::filesystem::path("/data/run/results.h5"));
  EXPECT_EQ(s.restart->step, std::optional<long>(20));
  // The resolved scenario is the run's own: a restarted run stores what the run it goes on stored.
  EXPECT_EQ(s.resolved_toml(), plain.resolved_toml());
  EXPECT_EQ(error_of(valid + "[restart]\nstep = 2\n").find("s.toml:"), 0U);
  EXPECT_NE(error_of(valid + "[restart]\nstep = 2\n").find("missing required key 'restart.from'"), std::string::npos);
  EXPECT_EQ(error_of(valid + "[restart]\nfrom = \"a.h5\"\nstep = -1\n"), "s.toml: key 'restart.step' must be 0 or more (got -1)");
}

TEST(ScenarioReader, ReadsTheElementAndNamesAnUnknownOne) {
  EXPECT_EQ(parse_scenario(valid, "s.toml", "/data").element, fem::Element::tet4);
  const std::string nodal = replaced(valid, "mesh = \"brain.msh\"", "mesh = \"brain.msh\"\nelement = \"nodal-pressure\"");
  const Scenario s = parse_scenario(nodal, "s.toml", "/data");
  EXPECT_EQ(s.element, fem::Element::nodal_pressure);
  EXPECT_EQ(parse_scenario(s.resolved_toml(), "resolved.toml", "/data").element, fem::Element::nodal_pressure);
  EXPECT_EQ(error_of(replaced(valid, "mesh = \"brain.msh\"", "mesh = \"brain.msh\"\nelement = \"nodal_pressure\"")),
            "s.toml: key 'element': unknown element 'nodal_pressure' (did you mean 'nodal-pressure'?): use tet4, "
            "nodal-pressure or tet10");
  const std::string tet10 = replaced(valid, "mesh = \"brain.msh\"", "mesh = \"brain.msh\"\nelement = \"tet10\"");
  EXPECT_EQ(parse_scenario(parse_scenario(tet10, "s.toml", "/data").resolved_toml(), "resolved.toml", "/data").element,
            fem::Element::tet10);
}

TEST(ScenarioReader, ReadsTheReductionOfTheStaticPart) {
  EXPECT_EQ(parse_scenario(valid, "s.toml", "/data").reduction.kind, &condensation::reduction_named("static"));
  const Scenario cb = parse_scenario(
      replaced(valid, "radius_mm = 25", "radius_mm = 25\nreduction = \"craig-bampton\"\nmodes = 10"), "s.toml", "/data");
  EXPECT_EQ(cb.reduction.kind, &condensation::reduction_named("craig-bampton"));
  EXPECT_EQ(cb.reduction.modes, 10);
  const Scenario again = parse_scenario(cb.resolved_toml(), "resolved.toml", "/data");
  EXPECT_EQ(again.reduction.label(), "craig-bampton-10");
  const Scenario cut = parse_scenario(
      replaced(valid, "radius_mm = 25", "radius_mm = 25\nreduction = \"craig-bampton\"\ncutoff_rad_s = 40.0"), "s.toml", "/data");
  EXPECT_EQ(cut.reduction.cutoff_rad_s, 40.0);
  EXPECT_EQ(parse_scenario(cut.resolved_toml(), "r.toml", "/data").reduction.cutoff_rad_s, 40.0);
  EXPECT_EQ(parse_scenario(replaced(valid, "radius_mm = 25", "radius_mm = 25\nreduction = \"guyan\""), "s.toml", "/data")
                .reduction.kind,
            &condensation::reduction_named("guyan"));
  const Scenario pod =
      parse_scenario(replaced(valid, "radius_mm = 25", "radius_mm = 25\nreduction = \"pod\"\nmodes = 40"), "s.toml", "/data");
  EXPECT_EQ(pod.reduction.label(), "pod-40");
  EXPECT_EQ(pod.reduction.snapshot_dt_s, pod.dt);  // trained on the run's own step and length
  EXPECT_EQ(pod.reduction.snapshot_steps, pod.steps);
  EXPECT_EQ(parse_scenario(pod.resolved_toml(), "r.toml", "/data").reduction.label(), "pod-40");
}

TEST(ScenarioReader, BadReductionsAreNamed) {
  EXPECT_NE(
      error_of(replaced(valid, "radius_mm = 25", "radius_mm = 25\nreduction = \"modal\"")).find("'roi.reduction' must be one of"),
      std::string::npos);
  EXPECT_NE(
      error_of(replaced(valid, "radius_mm = 25", "radius_mm = 25\nreduction = \"craig-bampton\"")).find("needs key 'roi.modes'"),
      std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "radius_mm = 25", "radius_mm = 25\nreduction = \"craig-bampton\"\nmodes = 0"))
                .find("'roi.modes' must be positive"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "radius_mm = 25", "radius_mm = 25\nmodes = 5")).find("belong to reduction"),
            std::string::npos);
  EXPECT_NE(
      error_of(replaced(valid, "radius_mm = 25", "radius_mm = 25\nreduction = \"pod\"")).find("needs a positive key 'roi.modes'"),
      std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "radius_mm = 25", "radius_mm = 25\nreduction = \"pod\"\nmodes = 4\ncutoff_rad_s = 9"))
                .find("'roi.cutoff_rad_s' belongs to reduction = \"craig-bampton\""),
            std::string::npos);
}

// Found by fuzzing: toml++ 3.3 reaches undefined behaviour on a stray non-ASCII character where
// a key is expected; TOML allows them only in strings and comments, and so do we.
TEST(ScenarioReader, NonAsciiOutsideStringsAndCommentsIsNamedAndInsideIsFine) {
  const std::string msg = error_of(replaced(valid, "[time]", "\xC2\xA1 = 1\n[time]"));
  EXPECT_NE(msg.find("s.toml:18:1: non-ASCII character outside a string or comment"), std::string::npos) << msg;
  // A stray quote inside a malformed value opens no string (fuzzing found `1111t"` then a non-ASCII character).
  EXPECT_NE(error_of("mesh =1111t\"\xC2\xB9=1\n").find("s.toml:1:13: non-ASCII character"), std::string::npos)
      << error_of("mesh =1111t\"\xC2\xB9=1\n");
  EXPECT_NE(error_of("m = \"\"\"a\\\n  \xCF\x9A\"\"\"\n").find("right after a line-ending backslash"), std::string::npos)
      << error_of("m = \"\"\"a\\\n  \xCF\x9A\"\"\"\n");
  // A non-ASCII character after a backslash (and blanks) in a string: fuzzing found `\` then U+03DA.
  for (const std::string bad :
       {"m = \"\"\"hehif-\n\\\xCF\x9A(yo\"\"\"\n", "m = \"\"\"a\\  \xCF\x9A\"\"\"\n", "m = \"a\\\xC3\xA9\"\n"})
    EXPECT_NE(error_of(bad).find("non-ASCII character after a backslash"), std::string::npos) << error_of(bad);
  EXPECT_NE(error_of("m = \"a\\\xC3\xA9\"\n").find("s.toml:1:8:"), std::string::npos) << error_of("m = \"a\\\xC3\xA9\"\n");
  // toml++ scans a bare value to its end (whitespace, ']', '}', ',' or '#') before refusing it:
  // a quote inside one opens no string. Each of these reached undefined behaviour in toml++.
  for (const std::string bare : {"1.", "+.", "1979-05-27.", "12:00.", "0x1.", "1{", "[1{", "tr."}) {
    const std::string text = "x = " + bare + "\"\xC3\xA9\"\n";
    const std::string column = std::to_string(6 + bare.size());
    EXPECT_NE(error_of(text).find("s.toml:1:" + column + ": non-ASCII character outside"), std::string::npos) << error_of(text);
  }
  // Where TOML lets a key or a value begin, a quote opens a string, over lines in an array.
  const std::string strings =
      "a.\"\xC3\xA9\" = 1\n[ \"\xC3\xA9\" ]\nx = [ # \xC3\xA9\n  1, \"\xC3\xA9\",\n  '\xC3\xA9',\n]\n"
      "y = { \"\xC3\xA9\" = '''\xC3\xA9''', b = [\"\xC3\xA9\"] }\n";
  EXPECT_EQ(error_of(strings).find("non-ASCII"), std::string::npos) << error_of(strings);
  const std::string fine = "\xEF\xBB\xBF# caf\xC3\xA9 \xC2\xB5m\n" + replaced(valid, "brain.msh", "caf\xC3\xA9/brain.msh");
  EXPECT_EQ(parse_scenario(fine, "s.toml", "/data").mesh, std::filesystem::path("/data/caf\xC3\xA9/brain.msh"));
}

TEST(ScenarioReader, SyntaxErrorNamesFileAndLine) {
  const std::string msg = error_of("mesh = \"a.msh\"\n[time\ndt_s = 1\n");
  EXPECT_NE(msg.find("s.toml:2:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("syntax error"), std::string::npos) << msg;
}

TEST(ScenarioReader, UnknownKeysAreErrorsNamingFileLineAndKey) {
  std::string msg = error_of(replaced(valid, "steps = 30", "steps = 30\nstpes = 3"));
  EXPECT_NE(msg.find("s.toml:21:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown key 'time.stpes'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("valid: atol, dt_s, integrator, rtol, steps"), std::string::npos) << msg;
  msg = error_of("colour = \"red\"\n" + valid);
  EXPECT_NE(msg.find("unknown key 'colour'"), std::string::npos) << msg;
}

TEST(ScenarioReader, WrongTypesAreErrorsNamingTheKey) {
  EXPECT_NE(error_of(replaced(valid, "dt_s = 0.01", "dt_s = \"fast\"")).find("'time.dt_s' must be a number"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "steps = 30", "steps = 30.5")).find("'time.steps' must be an integer"), std::string::npos);
  EXPECT_NE(
      error_of(replaced(valid, "force_N = [-0.01, 0, 0]", "force_N = [1, 2]")).find("'load.force_N' must be an array of three"),
      std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "fixed = [\"base\"]", "fixed = \"base\"")).find("'boundary.fixed' must be an array"),
            std::string::npos);
}

TEST(ScenarioReader, MissingRequiredKeysAreNamed) {
  EXPECT_NE(error_of(replaced(valid, "mesh = \"brain.msh\"", "")).find("missing required key 'mesh'"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "set = \"opening_left\"", "")).find("missing required key 'load.set'"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "rho_kg_m3 = 1040", "")).find("material.rho_kg_m3"), std::string::npos);
}

TEST(ScenarioReader, NonFiniteAndNonPhysicalValuesAreRejected) {
  EXPECT_NE(error_of(replaced(valid, "dt_s = 0.01", "dt_s = nan")).find("'time.dt_s' must be finite"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "ramp_s = 0.5", "ramp_s = inf")).find("'load.ramp_s' must be finite"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "force_N = [-0.01, 0, 0]", "force_N = [nan, 0, 0]")).find("finite"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "poisson = 0.45", "poisson = 0.5")).find("Poisson"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "poisson = 0.45", "poisson = -1.0")).find("Poisson"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "young_Pa = 3000.0", "young_Pa = -3.0")).find("Young"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "rho_kg_m3 = 1040", "rho_kg_m3 = 0")).find("density"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "alpha_per_s = 2.5", "alpha_per_s = -1")).find("alpha"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "dt_s = 0.01", "dt_s = 0")).find("'time.dt_s' must be positive"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "steps = 30", "steps = 0")).find("'time.steps' must be positive"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "radius_mm = 25", "radius_mm = -2")).find("roi.radius_mm"), std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "kind = \"ball\"", "kind = \"cube\"")).find("'roi.kind' must be one of"), std::string::npos);
}

TEST(ScenarioReader, GravityIsALoadOfItsOwn) {
  const Scenario s = parse_scenario(valid + "[[load]]\ngravity_m_s2 = [0, 0, -9.81]\nramp_s = 1.0\n", "s.toml", "/data");
  ASSERT_EQ(s.loads.size(), 2u);
  ASSERT_TRUE(s.loads[1].gravity.has_value());
  EXPECT_EQ(*s.loads[1].gravity, Vec3(0, 0, -9.81));
  EXPECT_NE(error_of(valid + "[[load]]\ngravity_m_s2 = [0, 0, -9.81]\nset = \"base\"\n").find("either gravity_m_s2"),
            std::string::npos);
  const Scenario again = parse_scenario(s.resolved_toml(), "r.toml", "/");
  EXPECT_EQ(*again.loads[1].gravity, Vec3(0, 0, -9.81));
}

TEST(ScenarioReader, MissingFileIsNamed) {
  try {
    read_scenario("/nonexistent/s.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/s.toml: cannot open"), std::string::npos);
  }
}

}  // namespace
}  // namespace roifem::scenario

namespace roifem::scenario {
namespace {

TEST(ScenarioReader, ReadsMaterialRegionsThatInheritTheBrainsKeys) {
  const std::string regions = replaced(valid, "[boundary]", R"([[material_region]]
set = "white_matter"
young_Pa = 4500.0
[[material_region]]
set = "csf"
preset = "brain"
mu_Pa = 100.0
alpha_per_s = 2.5
[boundary])");
  const Scenario s = parse_scenario(regions, "s.toml", "/data");
  ASSERT_EQ(s.material_regions.size(), 2u);
  const fem::Material& white = s.material_regions[0].material;
  EXPECT_EQ(s.material_regions[0].set, "white_matter");
  EXPECT_NEAR(white.young(), 4500, 1e-9);
  EXPECT_NEAR(white.poisson(), 0.45, 1e-12);  // from [material]
  EXPECT_EQ(white.rho, 1040);
  EXPECT_EQ(white.alpha, 2.5);
  const fem::Material& csf = s.material_regions[1].material;
  EXPECT_EQ(csf.mu, 100.0);
  EXPECT_EQ(csf.rho, fem::material_preset("brain").rho);  // from the preset
  const Scenario again = parse_scenario(s.resolved_toml(), "resolved.toml", "/data");
  ASSERT_EQ(again.material_regions.size(), 2u);
  EXPECT_EQ(again.material_regions[1].material.mu, 100.0);
  EXPECT_NEAR(again.material_regions[0].material.lambda, white.lambda, 1e-9 * white.lambda);
}

TEST(ScenarioReader, NamesABadMaterialRegion) {
  EXPECT_NE(error_of(replaced(valid, "[boundary]", "[[material_region]]\nyoung_Pa = 1.0\n[boundary]"))
                .find("missing required key 'material_region.set'"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "[boundary]", "[[material_region]]\nset = \"wm\"\npoisson = 0.5\n[boundary]"))
                .find("[[material_region]] 'wm': material: Poisson's ratio nu = 0.5 must lie in"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid, "[boundary]", "[[material_region]]\nset = \"wm\"\nshear = 1.0\n[boundary]")).find("shear"),
            std::string::npos);
}

}  // namespace
}  // namespace roifem::scenario

namespace roifem::scenario {
namespace {

TEST(ScenarioReader, ReadsTheMaterialModelAndSuggestsAMisspeltOne) {
  EXPECT_EQ(parse_scenario(valid, "s.toml", "/data").material.model, fem::MaterialModel::linear);
  const std::string neo = replaced(valid, "alpha_per_s = 2.5", "alpha_per_s = 2.5\nmodel = \"neo-hookean\"");
  const Scenario s = parse_scenario(neo, "s.toml", "/data");
  EXPECT_EQ(s.material.model, fem::MaterialModel::neo_hookean);
  EXPECT_EQ(parse_scenario(s.resolved_toml(), "r.toml", "/data").material.model, fem::MaterialModel::neo_hookean);
  const std::string message = error_of(replaced(valid, "alpha_per_s = 2.5", "alpha_per_s = 2.5\nmodel = \"neo-hooke\""));
  EXPECT_NE(message.find("s.toml"), std::string::npos) << message;
  EXPECT_NE(message.find("material model 'neo-hooke' is unknown (did you mean 'neo-hookean'?)"), std::string::npos) << message;
  EXPECT_NE(message.find("valid: linear, neo-hookean"), std::string::npos) << message;
}

TEST(ScenarioReader, AMaterialRegionKeepsTheBrainsLawUnlessItNamesItsOwn) {
  const std::string neo = replaced(valid, "alpha_per_s = 2.5", "alpha_per_s = 2.5\nmodel = \"neo-hookean\"");
  const Scenario inherits =
      parse_scenario(neo + "[[material_region]]\nset = \"csf\"\npreset = \"brain\"\nalpha_per_s = 2.5\n", "s.toml", "/data");
  EXPECT_EQ(inherits.material_regions.at(0).material.model, fem::MaterialModel::neo_hookean);
  const Scenario own =
      parse_scenario(neo + "[[material_region]]\nset = \"csf\"\nmu_Pa = 100\nmodel = \"linear\"\n", "s.toml", "/data");
  EXPECT_EQ(own.material_regions.at(0).material.model, fem::MaterialModel::linear);
  EXPECT_EQ(parse_scenario(own.resolved_toml(), "r.toml", "/data").material_regions.at(0).material.model,
            fem::MaterialModel::linear);
}

TEST(ScenarioReader, OgdenTermsTakeTheShearModulusAndReadBackFromTheResolvedText) {
  // One term: mu_1 is the material's mu (E = 3000, nu = 0.45).
  auto with_material = [](const std::string& keys) {
    std::string text = valid;
    const std::string old = "alpha_per_s = 2.5\n";
    return text.replace(text.find(old), old.size(), old + keys);
  };
  const Scenario one = parse_scenario(with_material("model = \"ogden\"\nogden_alpha = [-20.0]\n"), "s.toml", "/data");
  ASSERT_EQ(one.material.ogden.size(), 1u);
  EXPECT_EQ(one.material.ogden[0].mu, one.material.mu);
  EXPECT_EQ(one.material.ogden[0].alpha, -20.0);
  // Two terms with poisson: their sum is mu, and lambda = 2 mu nu / (1 - 2 nu).
  std::string two_terms = with_material("model = \"ogden\"\nogden_alpha = [-20.0, 4.0]\nogden_mu_Pa = [700.0, 300.0]\n");
  two_terms.replace(two_terms.find("young_Pa = 3000.0\n"), 18, "");
  const Scenario two = parse_scenario(two_terms, "s.toml", "/data");
  ASSERT_EQ(two.material.ogden.size(), 2u);
  EXPECT_EQ(two.material.mu, 1000.0);
  EXPECT_NEAR(two.material.lambda, 2 * 1000.0 * 0.45 / 0.1, 1e-9);
  for (const Scenario* s : {&one, &two}) {
    const Scenario again = parse_scenario(s->resolved_toml(), "resolved.toml", "/elsewhere");
    EXPECT_EQ(again.material.model, fem::MaterialModel::ogden);
    EXPECT_EQ(again.material.lambda, s->material.lambda);
    EXPECT_EQ(again.material.mu, s->material.mu);
    ASSERT_EQ(again.material.ogden.size(), s->material.ogden.size());
    for (std::size_t i = 0; i < s->material.ogden.size(); ++i) {
      EXPECT_EQ(again.material.ogden[i].mu, s->material.ogden[i].mu);
      EXPECT_EQ(again.material.ogden[i].alpha, s->material.ogden[i].alpha);
    }
  }
}

}  // namespace
}  // namespace roifem::scenario
