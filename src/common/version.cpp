// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/version.hpp"

namespace roifem {

std::string_view version() { return ROIFEM_VERSION; }  // CMake's project(VERSION), defined for this file alone

}  // namespace roifem
