// SPDX-License-Identifier: GPL-3.0-or-later
// roifem.Simulation: a scenario's model stepped from Python (simulation::ScenarioStepper), with its
// state as NumPy views and everything `roifem run` records readable between steps.
#include <climits>
#include <filesystem>
#include <map>
#include <optional>

#include "bindings.hpp"
#include "common/errors.hpp"
#include "common/timer.hpp"
#include "integrators/integrator_table.hpp"
#include "mesh_handle.hpp"
#include "scenario_handle.hpp"
#include "simulation/scenario_stepper.hpp"

namespace roifem::python {

namespace {

using simulation::ScenarioStepper;

class Simulation {
 public:
  Simulation(ScenarioHandle scenario, bool energy)
      : stepper_(std::make_shared<ScenarioStepper>(refusing_a_restart(scenario.scenario), energy)),
        handle_(std::move(scenario)) {}

  /// A Simulation steps from rest: a scenario's [restart] (which `roifem run` takes) is refused, not left out.
  static const scenario::Scenario& refusing_a_restart(const scenario::Scenario& sc) {
    if (sc.restart)
      throw InputError((sc.restart->where.empty() ? sc.file.string() : sc.restart->where) +
                       ": [restart]: roifem.Simulation steps from rest; `roifem run` goes on an earlier run");
    return sc;
  }

  /// The stepper, or ValueError once closed.
  ScenarioStepper& live() const {
    if (!stepper_) throw py::value_error("this roifem.Simulation is closed (arrays taken from it before stay valid)");
    return *stepper_;
  }
  const std::shared_ptr<ScenarioStepper>& shared() const {
    live();
    return stepper_;
  }
  void close() { stepper_.reset(); }
  bool is_open() const { return stepper_ != nullptr; }
  const ScenarioHandle& scenario() const { return handle_; }

  /// Steps `steps` times in C++, calling `observer(self)` after each (every `every` steps) and
  /// honouring Ctrl-C between steps (KeyboardInterrupt; the state is then that of the last step).
  /// An observer that closes the simulation ends the run there.
  long run(py::object self, long steps, const py::object& observer, long every) {
    const std::shared_ptr<ScenarioStepper> keep = shared();  // alive through the observer's calls
    if (steps < 0) throw InputError("run: steps = " + std::to_string(steps) + " must be >= 0");
    if (every <= 0) throw InputError("run: every = " + std::to_string(every) + " must be positive");
    if (!observer.is_none() && PyCallable_Check(observer.ptr()) == 0)
      throw py::type_error("run: observer must be callable, as observer(sim) after every `every`-th step (got " +
                           type_name(observer) + ")");
    for (long k = 1; k <= steps; ++k) {
      keep->step();
      if (!observer.is_none() && k % every == 0) observer(self);
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!is_open()) return k;
    }
    return steps;
  }

 private:
  std::shared_ptr<ScenarioStepper> stepper_;
  ScenarioHandle handle_;  ///< the scenario as given (Simulation.scenario)
};

/// A count given from Python: None, or an int that fits a long (InputError otherwise, naming `what`).
std::optional<long> count_of(py::handle value, const char* what) {
  if (value.is_none()) return std::nullopt;
  if (PyBool_Check(value.ptr()) || PyLong_Check(value.ptr()) == 0)
    throw py::type_error(std::string(what) + " must be an int (got " + type_name(value) + ")");
  int overflow = 0;
  const long count = PyLong_AsLongAndOverflow(value.ptr(), &overflow);
  if (overflow != 0)
    throw InputError(std::string(what) + " = " + std::string(py::str(value)) + " does not fit a 64-bit count (at most " +
                     std::to_string(LONG_MAX) + ")");
  return count;
}

py::dict stats_dict(const integrators::Stats& st) {
  py::dict d;
  for (const integrators::StatsField& f : integrators::stats_fields()) d[py::str(std::string(f.name))] = st.*f.member;
  d["factorization_s"] = st.factorization_s;
  return d;
}

py::array_t<double> vector_copy(const Vector& v, py::ssize_t cols) { return copied_array(v.data(), v.size(), cols); }

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<Simulation>(
      m, "Simulation",
      "A scenario's model (full, or the ROI with the static part condensed or reduced) and its integrator, "
      "stepped from Python on the grid t_k = k dt: the states equal `roifem run`'s bit for bit.\n\n"
      "Simulation(scenario, energy=True, **overrides): `scenario` a Scenario or a file; overrides as in "
      "Scenario.replace, plus the [time] table's integrator=, dt_s= (or dt=), steps=, rtol=, atol=. energy=False drops "
      "the energy ledger (one product with K and M per step).\n"
      "u and v are read-only views of the state (valid as long as they live, even after close()).")
      .def(py::init([](const py::object& scenario, bool energy, const py::kwargs& kwargs) {
             py::dict overrides, time;
             for (const auto& [key, value] : kwargs)
               if (std::string(py::str(key)) != "time") overrides[key] = value;
             // The [time] keys, given as time={...} or one by one (dt for short): each once.
             std::map<std::string, std::string> given;  // [time] key -> how it was given
             if (kwargs.contains("time")) {
               time = py::dict(kwargs["time"]);
               for (const auto& [key, value] : time) given[py::str(key)] = "time={'" + std::string(py::str(key)) + "': ...}";
             }
             for (const char* name : {"dt", "dt_s", "integrator", "steps", "rtol", "atol"}) {
               if (!kwargs.contains(name)) continue;
               const std::string key = std::string_view(name) == "dt" ? "dt_s" : name;
               if (given.count(key))
                 throw InputError("Simulation: [time] " + key + " is given twice, as " + given[key] + " and as " + name +
                                  "=: give it once");
               given[key] = std::string(name) + "=";
               time[key.c_str()] = kwargs[name];
               overrides.attr("pop")(name);
             }
             if (!time.empty()) overrides["time"] = time;
             ScenarioHandle sc = scenario_handle_of(scenario);
             if (!overrides.empty()) sc = with_overrides(sc, overrides);
             return Simulation(std::move(sc), energy);
           }),
           py::arg("scenario"), py::arg("energy") = true)
      .def(
          "step", [](Simulation& self) { self.live().step(); }, "One step of the grid, to t_{k+1}")
      .def(
          "step_to",
          [](const py::object& me, double t) {
            auto& self = me.cast<Simulation&>();
            return self.run(me, self.live().steps_to(t), py::none(), 1);
          },
          py::arg("t"),
          "Steps along the grid to its last point t_k <= t (s), which must be finite and ahead of sim.t; Ctrl-C "
          "stops it between two steps (KeyboardInterrupt). Returns the steps taken.")
      .def(
          "run",
          [](const py::object& me, const py::object& steps, const py::object& observer, long every) {
            auto& self = me.cast<Simulation&>();
            const ScenarioStepper& s = self.live();
            return self.run(me, count_of(steps, "run: steps").value_or(std::max(0L, s.scenario().steps - s.steps_taken())),
                            observer, every);
          },
          py::arg("steps") = py::none(), py::arg("observer") = py::none(), py::arg("every") = 1,
          "Runs `steps` steps (default: the rest of the scenario's), calling observer(sim) after every `every`-th; "
          "Ctrl-C stops it between two steps (KeyboardInterrupt). Returns the steps taken.")
      .def(
          "_steps_in_cpp",
          [](Simulation& self, long steps) {
            ScenarioStepper& s = self.live();
            Stopwatch clock;
            for (long k = 0; k < steps; ++k) s.step();
            return clock.seconds();
          },
          py::arg("steps"), "Benchmarks only: `steps` steps in a C++ loop; returns its wall time (s)")
      .def("close", &Simulation::close, "Frees the model; arrays taken before stay valid, later access is a ValueError")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](Simulation& self, const py::args&) { self.close(); })
      .def_property_readonly(
          "closed", [](const Simulation& self) { return !self.is_open(); }, "whether close() freed the model")
      .def_property_readonly(
          "t", [](const Simulation& self) { return self.live().state().t; }, "the time now (s): t_k = k dt after k steps")
      .def_property_readonly(
          "step_index", [](const Simulation& self) { return self.live().steps_taken(); }, "k: steps taken")
      .def_property_readonly(
          "dofs", [](const Simulation& self) { return self.live().model().system().size(); },
          "the number of unknowns of the integrated system (the length of u and v)")
      .def_property_readonly(
          "integrator", [](const Simulation& self) { return self.live().scenario().integrator; },
          "the integrator's name (roifem.integrators() lists them)")
      .def_property_readonly(
          "scenario", [](const Simulation& self) { return self.scenario(); }, "the roifem.Scenario it was made from")
      .def_property_readonly(
          "mesh",
          [](const Simulation& self) {
            const auto& owner = self.shared();
            return Mesh{std::shared_ptr<const mesh::TetMesh>(owner, &owner->model().mesh)};
          },
          "the model's mesh (keeps the simulation's model alive)")
      .def_property_readonly(
          "u",
          [](const Simulation& self) {
            const auto& owner = self.shared();
            return owned_view(owner->state().u.data(), owner->state().u.size(), 0, owner);
          },
          "displacement of the integrated unknowns (m; the ROI's first with an ROI), a read-only view updated by each step")
      .def_property_readonly(
          "v",
          [](const Simulation& self) {
            const auto& owner = self.shared();
            return owned_view(owner->state().v.data(), owner->state().v.size(), 0, owner);
          },
          "velocity (m/s), a read-only view like u")
      .def_property_readonly(
          "roi_nodes", [](const Simulation& self) { return copied_array(self.live().model().roi_nodes); },
          "the ROI's mesh nodes (#ROI, 0-based indices into mesh.nodes; empty for the full model)")
      .def_property_readonly(
          "roi_displacement_mm", [](const Simulation& self) { return copied_array(self.live().roi_displacement_mm(), 3); },
          "the ROI nodes' displacement (#ROI x 3, mm), as results.h5 records it")
      .def(
          "displacement", [](Simulation& self) { return vector_copy(self.live().displacement(), 3); },
          "every node's displacement (N x 3, m): the static part recovered, tools on their paths")
      .def(
          "displacement_mm", [](Simulation& self) { return vector_copy(self.live().displacement() / mm, 3); },
          "every node's displacement (N x 3, mm, as results.h5's fields): displacement() in millimetres")
      .def_property_readonly(
          "energy",
          [](const Simulation& self) -> py::object {
            const model::EnergyLedger* e = self.live().energy();
            if (!e) return py::none();
            py::dict d;
            d["kinetic_J"] = e->kinetic();
            d["strain_J"] = e->strain();
            d["dissipated_J"] = e->dissipated();
            d["external_work_J"] = e->external_work();
            d["tool_work_J"] = e->tool_work();
            d["balance_residual_J"] = e->balance_residual();
            return d;
          },
          "the energy ledger now (J): kinetic, strain, dissipated, external and tools' work, and the balance "
          "E + D - W - W_tools - E_0 (zero to round-off for the trapezoidal rule); None with energy=False")
      .def(
          "reaction_forces",
          [](Simulation& self) {
            ScenarioStepper& s = self.live();
            const model::ReactionForces& r = s.reactions();
            const Vector forces = s.reaction_forces();
            py::dict d;
            d["nodes"] = copied_array(r.nodes());
            d["forces_N"] = vector_copy(forces, 3);
            const Vec3 total = forces.reshaped(3, forces.size() / 3).rowwise().sum();
            d["total_N"] = vector_copy(total, 0);
            return d;
          },
          "the supports' reactions on the tissue: nodes (the fixed ones), forces_N (#fixed x 3) and total_N")
      .def(
          "tool_forces",
          [](const Simulation& self) {
            const ScenarioStepper& s = self.live();
            const Vector F = s.tool_forces();
            py::dict d;
            const auto& tools = s.model().tools.tools();
            for (std::size_t a = 0; a < tools.size(); ++a)
              d[tools[a].name.c_str()] = vector_copy(F.segment<3>(3 * static_cast<Index>(a)), 0);
            return d;
          },
          "each tool's force on the tissue (N), by name (the surgeon feels its opposite)")
      .def_property_readonly(
          "stats", [](const Simulation& self) { return stats_dict(self.live().integrator().stats()); },
          "the integrator's counters: steps, rhs_evals, jac_evals, lin_setups, lin_solves, failed_steps, lin_iterations, "
          "nonlinear_iterations, indefinite_steps, system_changes (integrators/stats.hpp's table), factorization_s")
      .def("__repr__", [](const Simulation& self) {
        if (!self.is_open()) return std::string("<roifem.Simulation (closed)>");
        const ScenarioStepper& s = self.live();
        return "<roifem.Simulation " + s.scenario().file.string() + ": " + std::to_string(s.model().system().size()) + " dofs, " +
               s.scenario().integrator + ", step " + std::to_string(s.steps_taken()) + ">";
      });

  m.def(
      "integrators",
      [] {
        py::list out;
        for (const auto& info : integrators::integrator_table()) {
          py::dict d;
          d["name"] = info.name;
          d["order"] = info.order;
          d["explicit"] = info.is_explicit;
          d["fixed_step"] = info.fixed_step;
          d["adaptive"] = info.adaptive;
          d["summary"] = info.summary;
          out.append(d);
        }
        return out;
      },
      "Every integrator by name (the scenario's [time] integrator), with its order, whether it takes a fixed step "
      "and tolerances (rtol, atol), and a one-line summary");
}

}  // namespace roifem::python
