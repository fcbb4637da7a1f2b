// SPDX-License-Identifier: GPL-3.0-or-later
#include "experiments/error_budget.hpp"
#include "common/format.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <ostream>
#include <sstream>

#include "common/errors.hpp"
#include "common/timer.hpp"
#include "experiments/calculix_static.hpp"
#include "experiments/convergence_study.hpp"
#include "experiments/model_error.hpp"
#include "fem/static_solve.hpp"
#include "integrators/trapezoid.hpp"
#include "io/csv.hpp"
#include "io/result_cache.hpp"
#include "mesh/brain_mesh.hpp"
#include "mesh/mesh_checks.hpp"
#include "mesh/point_locator.hpp"
#include "model/modal_reference.hpp"
#include "simulation/progress.hpp"

namespace roifem::experiments {

double ErrorCurve::peak() const { return max.empty() ? 0 : *std::max_element(max.begin(), max.end()); }

double ErrorCurve::steady_mean() const {
  const std::size_t from = mean.size() > 100 ? 100 : 0;
  if (mean.size() == from) return 0;
  return std::accumulate(mean.begin() + static_cast<std::ptrdiff_t>(from), mean.end(), 0.0) /
         static_cast<double>(mean.size() - from);
}

namespace {

/// The walls pulled apart by force_N each, ramped (the paper's load).
std::vector<model::SetLoad> opening_loads(double force_N) {
  return {{"opening_left", Vec3(-force_N, 0, 0), model::Ramp{0}, std::nullopt},
          {"opening_right", Vec3(force_N, 0, 0), model::Ramp{0}, std::nullopt}};
}

/// Per step, the mean and max over `nodes` of |a(node) - b(node)|; b gives the other field at a node.
template <class Other>
ErrorCurve distances(const std::vector<int>& nodes, const std::vector<Vector>& a, Other b) {
  ErrorCurve c;
  for (std::size_t k = 0; k < a.size(); ++k) {
    double sum = 0, worst = 0;
    for (int n : nodes) {
      const double d = (a[k].segment<3>(3 * static_cast<Index>(n)) - b(k, n)).norm() / mm;
      sum += d;
      worst = std::max(worst, d);
    }
    c.mean.push_back(sum / static_cast<double>(nodes.size()));
    c.max.push_back(worst);
  }
  return c;
}

/// The finer reference of the same body and load.
struct FinerReference {
  mesh::TetMesh mesh;
  model::FemModel full;
};

std::unique_ptr<FinerReference> build_reference(const BudgetInput& in, const ErrorBudgetOptions& o,
                                                const std::filesystem::path& out, std::ostream& log) {
  const Stopwatch clock;
  auto r = std::make_unique<FinerReference>();
  mesh::TetMesh linear = std::move(mesh::generate_brain_mesh(o.reference_nodes, out / "reference" / "brain.msh").mesh);
  mesh::check_mesh(linear);
  r->mesh = fem::element_mesh(std::move(linear), o.reference_element);
  r->full = model::build_fem_model(r->mesh, in.full->material, in.fixed_sets, opening_loads(in.force_N), {}, o.reference_element);
  log << format("  space reference: the brain at %lld nodes (%lld dofs), element %s, built in %.1f s\n",
                static_cast<long long>(r->mesh.num_vertices()), static_cast<long long>(r->full.system.size()),
                std::string(fem::element_name(o.reference_element)).c_str(), clock.seconds());
  return r;
}

double static_opening_mm(const model::FemModel& full) {
  const Vector u = full.dofs->expand(fem::solve_static(full.system.K, full.system.load.at(1e30), *full.dofs));
  return opening_widening(*full.mesh, u) / mm;
}

/// What the budget needs of the reference: its vertex count, its static opening, and its
/// unit-slope run read at the probed nodes' positions (steps 0..steps, 3 per node).
struct SpaceReference {
  Index nodes = 0;
  double opening_mm = 0;
  std::vector<Vector> slope;
};

/// Everything the reference's figures depend on, for the cache.
std::string space_reference_key(const BudgetInput& in, const ErrorBudgetOptions& o, const std::vector<int>& probed) {
  const fem::Material& m = in.full->material;
  std::string key = "error budget: space reference\nnodes " + std::to_string(o.reference_nodes) + "\nelement " +
                    std::string(fem::element_name(o.reference_element)) + "\nmaterial " + io::exact(m.lambda) + " " +
                    io::exact(m.mu) + " " + io::exact(m.rho) + " " + io::exact(m.alpha) + "\nforce " + io::exact(in.force_N) +
                    "\ndt " + io::exact(in.dt) + "\nsteps " + std::to_string(in.steps) + "\nfixed";
  for (const auto& set : in.fixed_sets) key += " " + set;
  key += "\nprobed at";
  for (const int n : probed) {
    const Vec3 x = in.full->mesh->node(n);
    key += " " + io::exact(x.x()) + "," + io::exact(x.y()) + "," + io::exact(x.z());
  }
  return key;
}

SpaceReference space_reference(const BudgetInput& in, const ErrorBudgetOptions& o, const std::vector<int>& probed,
                               const std::filesystem::path& out, std::ostream& log) {
  const io::ResultCache cache(o.cache);
  const std::string key = space_reference_key(in, o, probed);
  const auto width = static_cast<std::size_t>(3 * probed.size());
  if (const auto kept = cache.load(key); kept && kept->size() == 2 + static_cast<std::size_t>(in.steps + 1) * width) {
    SpaceReference r{.nodes = static_cast<Index>((*kept)[0]), .opening_mm = (*kept)[1], .slope = {}};
    for (long k = 0; k <= in.steps; ++k)
      r.slope.emplace_back(
          Eigen::Map<const Vector>(kept->data() + 2 + static_cast<std::size_t>(k) * width, static_cast<Index>(width)));
    log << format("  space reference: the brain at %lld nodes (%s), read from the cache (%s)\n", static_cast<long long>(r.nodes),
                  std::string(fem::element_name(o.reference_element)).c_str(), cache.file_of(key).c_str());
    return r;
  }
  const std::unique_ptr<FinerReference> reference = build_reference(in, o, out, log);
  const mesh::PointLocator locator(reference->mesh);
  std::vector<mesh::PointLocation> located;
  located.reserve(probed.size());
  for (const int n : probed) located.push_back(locator.locate(in.full->mesh->node(n)));
  SpaceReference r{.nodes = reference->mesh.num_vertices(), .opening_mm = static_opening_mm(reference->full), .slope = {}};
  r.slope = unit_slope_run(
      reference->full, in.dt, in.steps,
      [&](const Vector& u) {
        Vector at(static_cast<Index>(width));
        for (std::size_t i = 0; i < probed.size(); ++i)
          at.segment<3>(3 * static_cast<Index>(i)) = mesh::PointLocator::interpolate(located[i], u);
        return at;
      },
      "reference", log);
  std::vector<double> kept{static_cast<double>(r.nodes), r.opening_mm};
  for (const Vector& w : r.slope) kept.insert(kept.end(), w.data(), w.data() + w.size());
  if (const std::string why = cache.store(key, kept); !why.empty())
    log << "  warning: the reference is not cached (" << why << ")\n";
  else if (cache.enabled())
    log << "  the reference is cached for the next run: " << cache.file_of(key).string() << '\n';
  return r;
}

/// What the paper mesh's model is, for the cache's keys: the material, the force, the supports and
/// the mesh (every node, tetrahedron and named set).
std::string paper_model_key(const BudgetInput& in) {
  const mesh::TetMesh& mesh = *in.full->mesh;
  const fem::Material& m = in.full->material;
  std::string key = "material " + io::exact(m.lambda) + " " + io::exact(m.mu) + " " + io::exact(m.rho) + " " +
                    io::exact(m.alpha) + "\nforce " + io::exact(in.force_N) + "\nfixed";
  for (const auto& set : in.fixed_sets) key += " " + set;
  key += "\nnodes";
  for (int n = 0; n < mesh.num_nodes(); ++n)
    for (int c = 0; c < 3; ++c) key += " " + io::exact(mesh.node(n)[c]);
  key += "\ntets";
  for (const auto& t : mesh.tets)
    for (int a = 0; a < 4; ++a) key += " " + std::to_string(t[a]);
  for (const auto& [name, set] : mesh.sets) {
    key += "\nset " + name;
    for (const int n : set.nodes) key += " " + std::to_string(n);
  }
  return key;
}

std::string model_error_key(const BudgetInput& in) {
  return "error budget: CalculiX NLGEOM at the full load\n" + paper_model_key(in);
}

/// The exact modal solution of the paper mesh's model at the probed nodes (3 per node), per ramp
/// and step 1..steps: from the cache, or by the dense eigensolution (then cached).
std::vector<std::vector<Vector>> exact_at_probed(const BudgetInput& in, const std::vector<int>& probed,
                                                 const io::ResultCache& cache, std::ostream& log) {
  std::string key = "error budget: the exact modal solution\n" + paper_model_key(in) + "\ndt " + io::exact(in.dt) + "\nsteps " +
                    std::to_string(in.steps) + "\nramps";
  for (const double ramp : in.ramps_s) key += " " + io::exact(ramp);
  key += "\nprobed";
  for (const int n : probed) key += " " + std::to_string(n);
  const auto width = static_cast<Index>(3 * probed.size());
  const std::size_t per_ramp = static_cast<std::size_t>(in.steps) * static_cast<std::size_t>(width);
  std::vector<std::vector<Vector>> exact(in.ramps_s.size());
  if (const auto kept = cache.load(key); kept && kept->size() == in.ramps_s.size() * per_ramp) {
    for (std::size_t r = 0; r < exact.size(); ++r)
      for (long k = 0; k < in.steps; ++k)
        exact[r].emplace_back(Eigen::Map<const Vector>(kept->data() + r * per_ramp + static_cast<std::size_t>(k * width), width));
    log << "  time: the exact modal solution read from the cache (" << cache.file_of(key).string() << ")\n";
    return exact;
  }
  const Stopwatch clock;
  const model::ModalReference modal(in.full->system, model::State::at_rest(in.full->system.size()));
  std::vector<double> kept;
  kept.reserve(in.ramps_s.size() * per_ramp);
  for (std::size_t r = 0; r < exact.size(); ++r) {
    const model::ModalReference ramped = modal.with_ramp(in.ramps_s[r]);
    for (long k = 1; k <= in.steps; ++k) {
      const double t = in.dt * static_cast<double>(k);
      const Vector u = in.full->displacement(ramped.displacement(t), t);
      Vector at(width);
      for (std::size_t i = 0; i < probed.size(); ++i) at.segment<3>(3 * static_cast<Index>(i)) = u.segment<3>(3 * probed[i]);
      kept.insert(kept.end(), at.data(), at.data() + at.size());
      exact[r].push_back(std::move(at));
    }
  }
  log << format("  time: the exact modal solution of the paper mesh's model in %.1f s\n", clock.seconds());
  if (const std::string why = cache.store(key, kept); !why.empty())
    log << "  warning: the exact modal solution is not cached (" << why << ")\n";
  return exact;
}

/// CalculiX's answer at the full load, linear and NLGEOM: from the cache, or computed (then cached).
ModelErrorStudy model_error_study(const BudgetInput& in, const std::filesystem::path& out, const io::ResultCache& cache,
                                  std::ostream& log) {
  const std::string key = model_error_key(in);
  const auto n = static_cast<std::size_t>(3 * in.full->mesh->num_nodes());
  if (const auto kept = cache.load(key); kept && kept->size() == 1 + 2 * n) {
    ModelErrorStudy study;
    study.full_load_reached = (*kept)[0] != 0;
    study.u_linear = Eigen::Map<const Vector>(kept->data() + 1, static_cast<Index>(n));
    study.u_nonlinear = Eigen::Map<const Vector>(kept->data() + 1 + n, static_cast<Index>(n));
    log << "  model: CalculiX's answer read from the cache (" << cache.file_of(key).string() << ")\n";
    return study;
  }
  if (!calculix_available()) return {};
  ModelErrorStudy study = measure_model_error(*in.full->mesh, in.full->material, in.fixed_sets, opening_loads(in.force_N), {1.0},
                                              out / "calculix", log);
  std::vector<double> kept{study.full_load_reached ? 1.0 : 0.0};
  if (study.full_load_reached) {
    kept.insert(kept.end(), study.u_linear.data(), study.u_linear.data() + study.u_linear.size());
    kept.insert(kept.end(), study.u_nonlinear.data(), study.u_nonlinear.data() + study.u_nonlinear.size());
    if (const std::string why = cache.store(key, kept); !why.empty())
      log << "  warning: CalculiX's answer is not cached (" << why << ")\n";
  }
  return study;
}

void model_error_into(const BudgetInput& in, const std::filesystem::path& out, const io::ResultCache& cache, ErrorBudget& budget,
                      std::ostream& log) {
  ModelErrorStudy study;
  try {
    study = model_error_study(in, out, cache, log);
  } catch (const SolverError& e) {  // CalculiX found no solution at this load: the rest of the budget stands
    budget.model_note = std::string("not measured: ") + e.what();
    log << "  model: " << budget.model_note << '\n';
    return;
  }
  if (!study.full_load_reached && !calculix_available()) {
    budget.model_note = "not measured: CalculiX (ccx) is not installed (scripts/setup.sh installs calculix-ccx)";
    return;
  }
  if (!study.full_load_reached) {
    budget.model_note = "not measured: CalculiX's nonlinear solution stopped before the full load";
    return;
  }
  for (const auto& [name, nodes] : in.setups) {
    // The same measure as the other sources, at one "step": the static full load.
    const ErrorCurve model =
        distances(nodes, {study.u_linear}, [&](std::size_t, int n) -> Vec3 { return study.u_nonlinear.segment<3>(3 * n); });
    for (auto& e : budget.entries)
      if (e.setup == name) {
        e.model_max_mm = model.max.front();
        e.model_mean_mm = model.mean.front();
      }
  }
}

void rank(BudgetEntry& e) {
  std::vector<std::pair<double, std::string>> peaks{
      {e.space.peak(), "space"}, {e.time.peak(), "time"}, {e.reduction.peak(), "reduction"}};
  if (e.model_max_mm) peaks.emplace_back(*e.model_max_mm, "model");
  if (e.model_dynamic) peaks.emplace_back(e.model_dynamic->peak(), "model (dynamic)");
  std::sort(peaks.rbegin(), peaks.rend());
  e.dominant = peaks[0].second;
  e.dominance = peaks[1].first > 0 ? peaks[0].first / peaks[1].first : 0;
}

}  // namespace

std::vector<Vector> unit_slope_run(const model::FemModel& full, double dt, long steps,
                                   const std::function<Vector(const Vector&)>& read) {
  std::ostringstream quiet;
  return unit_slope_run(full, dt, steps, read, "", quiet);
}

std::vector<Vector> unit_slope_run(const model::FemModel& full, double dt, long steps,
                                   const std::function<Vector(const Vector&)>& read, const std::string& label,
                                   std::ostream& log) {
  const Stopwatch clock;
  const double t_end = dt * static_cast<double>(steps);
  model::SecondOrderSystem system = full.system;
  system.load = full.system.load.with_ramp(model::Ramp{t_end});  // f t / t_end up to t_end
  integrators::Trapezoid trapezoid(dt);
  model::State state = model::State::at_rest(system.size());
  trapezoid.reset(system, state);
  const double factorization_s = clock.seconds();
  std::vector<Vector> w{Vector(t_end * read(full.displacement(state.u, 0.0)))};
  simulation::ProgressReporter progress(label, steps);
  const long tenth = steps >= 50 ? steps / 10 : 0;
  for (long k = 1; k <= steps; ++k) {
    trapezoid.step(state);
    w.emplace_back(t_end * read(full.displacement(state.u, state.t)));
    if (!label.empty()) progress.update(k);
    if (!label.empty() && k == tenth) {
      const double stepping_s = clock.seconds() - factorization_s;
      log << format("  %s: factored in %.1f s, %ld of %ld steps in %.1f s; about %.0f s to go\n", label.c_str(), factorization_s,
                    k, steps, stepping_s, stepping_s / static_cast<double>(k) * static_cast<double>(steps - k))
          << std::flush;
    }
  }
  return w;
}

std::vector<Vector> ramp_response(const std::vector<Vector>& w, double T, double dt) {
  const auto m = static_cast<long>(std::lround(T / dt));
  if (m < 1 || std::abs(static_cast<double>(m) * dt - T) > 1e-9 * T)
    throw InputError(format("error budget: the ramp %g s is not a positive multiple of dt = %g s", T, dt));
  std::vector<Vector> u;
  for (std::size_t k = 1; k < w.size(); ++k)
    u.emplace_back((w[k] - w[k >= static_cast<std::size_t>(m) ? k - static_cast<std::size_t>(m) : 0]) / T);
  return u;
}

ErrorBudget measure_error_budget(const BudgetInput& in, const ErrorBudgetOptions& o, const std::filesystem::path& out,
                                 std::ostream& log) {
  if (in.setups.size() != in.reduction.size()) throw Error("internal: error budget: a reduction curve per setup is needed");
  log << "\nerror budget: space, time, reduction and model error on the ROI nodes\n";
  ErrorBudget budget;
  const mesh::TetMesh& mesh = *in.full->mesh;
  std::vector<int> probed;  // every ROI node once
  std::vector<Index> slot(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (const auto& [name, nodes] : in.setups)
    for (int n : nodes)
      if (slot[static_cast<std::size_t>(n)] < 0) {
        slot[static_cast<std::size_t>(n)] = static_cast<Index>(probed.size());
        probed.push_back(n);
      }
  // The reference read at the ROI nodes' positions, 3 per node in `probed` order, at each step of its
  // unit-slope run: from the cache, or computed (then cached).
  std::vector<Vector> fine_slope;
  if (o.reference_nodes > 0) {
    const SpaceReference space = space_reference(in, o, probed, out, log);
    fine_slope = space.slope;
    budget.reference_nodes = space.nodes;
    budget.reference_element = fem::element_name(o.reference_element);
    const double coarse = static_opening_mm(*in.full);
    budget.reference_opening_error_pct = 100 * (coarse - space.opening_mm) / space.opening_mm;
    log << format("  static opening: %.3f mm on the paper mesh, %.3f mm on the reference (%+.1f%%)\n", coarse, space.opening_mm,
                  budget.reference_opening_error_pct);
  }
  // One unit-slope run of each model serves every ramp (ramp_response); one eigensolution too.
  const auto whole = [](const Vector& u) -> Vector { return u; };
  const std::vector<Vector> coarse_slope = unit_slope_run(*in.full, in.dt, in.steps, whole);
  const std::vector<std::vector<Vector>> exact = exact_at_probed(in, probed, io::ResultCache(o.cache), log);
  for (std::size_t r = 0; r < in.ramps_s.size(); ++r) {
    const double ramp = in.ramps_s[r];
    const std::vector<Vector> coarse = ramp_response(coarse_slope, ramp, in.dt);
    const std::vector<Vector> fine = fine_slope.empty() ? std::vector<Vector>{} : ramp_response(fine_slope, ramp, in.dt);
    for (std::size_t s = 0; s < in.setups.size(); ++s) {
      BudgetEntry e{.setup = in.setups[s].first, .ramp_s = ramp};
      const auto& nodes = in.setups[s].second;
      e.time = distances(nodes, coarse, [&](std::size_t k, int n) -> Vec3 {
        return exact[r][k].segment<3>(3 * slot[static_cast<std::size_t>(n)]);
      });
      if (!fine_slope.empty())
        e.space = distances(nodes, coarse, [&](std::size_t k, int n) -> Vec3 {
          return fine[k].segment<3>(3 * slot[static_cast<std::size_t>(n)]);
        });
      e.reduction = in.reduction[s][r];
      if (!in.model_dynamic.empty()) e.model_dynamic = in.model_dynamic[s][r];
      if (!in.hybrid.empty()) e.hybrid = in.hybrid[s][r];
      budget.entries.push_back(std::move(e));
    }
  }
  if (o.model_error)
    model_error_into(in, out, io::ResultCache(o.cache), budget, log);
  else
    budget.model_note = "not measured (switched off)";
  for (auto& e : budget.entries) rank(e);
  std::stable_sort(budget.entries.begin(), budget.entries.end(),
                   [](const BudgetEntry& a, const BudgetEntry& b) { return a.setup < b.setup; });
  return budget;
}

void print_error_budget(const ErrorBudget& b, std::ostream& log) {
  log << "\nError budget on the ROI nodes (mm): peak over the run of the largest nodal error / steady mean (after step 100)\n";
  if (b.reference_nodes > 0)
    log << format(
        "  space: the paper mesh against the brain at %lld nodes (%s); the paper mesh's static opening differs "
        "from the reference's by %+.1f%%\n",
        static_cast<long long>(b.reference_nodes), b.reference_element.c_str(), b.reference_opening_error_pct);
  log << "  time: trapezoidal rule at the paper's dt against the exact modal solution; reduction: condensed against full;\n"
         "  model: small strain against CalculiX NLGEOM, static at the full load"
      << (b.model_note.empty() ? "" : " (" + b.model_note + ")") << "\n";
  const bool large_deformation = !b.entries.empty() && b.entries.front().model_dynamic;
  if (large_deformation)
    log << "  model (dynamic): the full linear model against the full neo-Hookean one; hybrid: the nonlinear ROI over the\n"
           "  linear condensed remainder against the full neo-Hookean model (what is left with the law in the ROI)\n";
  auto pair = [](const ErrorCurve& c) { return format("%7.3f / %7.3f", c.peak(), c.steady_mean()); };
  log << format("%-7s %5s  %17s  %17s  %17s  %15s  ", "setup", "ramp", "space", "time", "reduction", "model (static)")
      << (large_deformation ? format("%17s  %17s  ", "model (dynamic)", "hybrid") : std::string()) << "dominant\n";
  for (const auto& e : b.entries) {
    const std::string model = e.model_max_mm ? format("%6.3f / %6.3f", *e.model_max_mm, *e.model_mean_mm) : std::string("-");
    log << format("%-7s %4.1fs  %17s  %17s  %17s  %15s  ", e.setup.c_str(), e.ramp_s,
                  (b.reference_nodes > 0 ? pair(e.space) : std::string("-")).c_str(), pair(e.time).c_str(),
                  pair(e.reduction).c_str(), model.c_str())
        << (large_deformation ? format("%17s  %17s  ", pair(*e.model_dynamic).c_str(), e.hybrid ? pair(*e.hybrid).c_str() : "-")
                              : std::string())
        << format("%s (%.1fx the next)\n", e.dominant.c_str(), e.dominance);
  }
}

void write_error_budget_csv(const ErrorBudget& b, double dt, const std::filesystem::path& out) {
  // The large-deformation paper's columns only where it measured them: the linear paper's file is unchanged.
  const bool large_deformation = !b.entries.empty() && b.entries.front().model_dynamic;
  io::CsvWriter csv(out / "error_budget.csv",
                    std::string("setup,ramp_s,step,t_s,space_mean_mm,space_max_mm,time_mean_mm,time_max_mm,reduction_mean_mm,"
                                "reduction_max_mm,model_max_mm") +
                        (large_deformation ? ",model_dynamic_mean_mm,model_dynamic_max_mm,hybrid_mean_mm,hybrid_max_mm" : ""));
  for (const auto& e : b.entries)
    for (std::size_t k = 0; k < e.time.max.size(); ++k) {
      auto at = [k](const std::vector<double>& v) { return k < v.size() ? format("%.6g", v[k]) : std::string(); };
      std::string row = format("%s,%g,%zu,%g,", e.setup.c_str(), e.ramp_s, k + 1, dt * static_cast<double>(k + 1)) +
                        at(e.space.mean) + "," + at(e.space.max) + "," + at(e.time.mean) + "," + at(e.time.max) + "," +
                        at(e.reduction.mean) + "," + at(e.reduction.max) + "," +
                        (e.model_max_mm ? format("%.6g", *e.model_max_mm) : std::string());
      if (large_deformation) {
        const ErrorCurve none;
        const ErrorCurve& hybrid = e.hybrid ? *e.hybrid : none;
        row += "," + at(e.model_dynamic->mean) + "," + at(e.model_dynamic->max) + "," + at(hybrid.mean) + "," + at(hybrid.max);
      }
      csv.row(row);
    }
  csv.close();
}

}  // namespace roifem::experiments
