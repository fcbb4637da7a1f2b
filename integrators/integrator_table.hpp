// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// The one list of integrators: a row per name with its traits (integrator_info.hpp). The factory
/// (make_integrator), the stability search, `roifem compare`, `--help` and the guide's list all
/// read it. Each family exports its own rows beside its methods; the table joins them, so that
/// adding an integrator touches its own files and one line of integrator_table.cpp.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "integrators/integrator_info.hpp"

namespace roifem::integrators {

/// Every integrator, in the order `compare` runs them and `--help` lists them.
std::span<const IntegratorInfo> integrator_table();
/// The row of `name`; InputError listing the valid names for an unknown one.
const IntegratorInfo& integrator_info(std::string_view name);
std::vector<std::string> integrator_names();
/// "trapezoid, trapezoid-cg, ...": for messages and --help.
std::string integrator_name_list();
/// The table as text, a line per integrator (name, order, explicit/implicit, fixed/adaptive, linear
/// solver, summary): the footer of `roifem run --help` and `roifem compare --help`.
std::string integrator_table_text();
std::string_view family_name(Family family);
std::string_view linear_solver_name(LinearSolver solver);

}  // namespace roifem::integrators
