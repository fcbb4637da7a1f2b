# SPDX-License-Identifier: GPL-3.0-or-later
# FindSuiteSparse: CHOLMOD and KLU from SuiteSparse 5.x (Debian 12 ships no CMake config for them).
# Defines SuiteSparse_FOUND and the imported targets SuiteSparse::CHOLMOD and SuiteSparse::KLU.
find_path(SuiteSparse_INCLUDE_DIR NAMES cholmod.h PATH_SUFFIXES suitesparse)
set(_ss_components cholmod klu amd colamd camd ccolamd btf suitesparseconfig)
set(_ss_required SuiteSparse_INCLUDE_DIR)
foreach(_c IN LISTS _ss_components)
  find_library(SuiteSparse_${_c}_LIBRARY NAMES ${_c})
  list(APPEND _ss_required SuiteSparse_${_c}_LIBRARY)
  mark_as_advanced(SuiteSparse_${_c}_LIBRARY)
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse REQUIRED_VARS ${_ss_required})
if(SuiteSparse_FOUND AND NOT TARGET SuiteSparse::CHOLMOD)
  foreach(_c IN LISTS _ss_components)
    add_library(SuiteSparse::${_c} UNKNOWN IMPORTED)
    set_target_properties(SuiteSparse::${_c} PROPERTIES IMPORTED_LOCATION "${SuiteSparse_${_c}_LIBRARY}"
                          INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
  endforeach()
  add_library(SuiteSparse::CHOLMOD INTERFACE IMPORTED)
  target_link_libraries(SuiteSparse::CHOLMOD INTERFACE SuiteSparse::cholmod SuiteSparse::amd SuiteSparse::colamd
                        SuiteSparse::camd SuiteSparse::ccolamd SuiteSparse::suitesparseconfig)
  add_library(SuiteSparse::KLU INTERFACE IMPORTED)
  target_link_libraries(SuiteSparse::KLU INTERFACE SuiteSparse::klu SuiteSparse::btf SuiteSparse::amd
                        SuiteSparse::colamd SuiteSparse::suitesparseconfig)
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR)
