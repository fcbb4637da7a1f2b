// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// roifem's version: CMake's project(VERSION), printed by --version, stored in every HDF5 file
/// (attribute roifem_version) and on the first line of every CSV file ("# roifem VERSION").
#include <string_view>

namespace roifem {

std::string_view version();

}  // namespace roifem
