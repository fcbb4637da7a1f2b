# SPDX-License-Identifier: GPL-3.0-or-later
# MUMPS' C interface for doubles, MPI build (Debian: libmumps-dev). Defines MUMPS::dmumps.
find_path(MUMPS_INCLUDE_DIR dmumps_c.h)
find_library(MUMPS_DMUMPS_LIBRARY NAMES dmumps)
find_library(MUMPS_COMMON_LIBRARY NAMES mumps_common)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MUMPS REQUIRED_VARS MUMPS_DMUMPS_LIBRARY MUMPS_COMMON_LIBRARY MUMPS_INCLUDE_DIR)
if(MUMPS_FOUND AND NOT TARGET MUMPS::dmumps)
  add_library(MUMPS::dmumps INTERFACE IMPORTED)
  set_target_properties(MUMPS::dmumps PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${MUMPS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${MUMPS_DMUMPS_LIBRARY};${MUMPS_COMMON_LIBRARY}")
endif()
mark_as_advanced(MUMPS_INCLUDE_DIR MUMPS_DMUMPS_LIBRARY MUMPS_COMMON_LIBRARY)
