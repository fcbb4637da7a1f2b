# SPDX-License-Identifier: GPL-3.0-or-later
# NIfTI-1/2 image I/O (Debian's libnifti2-dev). Its own NIFTIConfig.cmake names
# /usr/lib/libznz.so.3.0.0, a path the package does not install, so it cannot be used; this finds
# the header and the libraries instead. Defines NIfTI::nifti2.
find_path(NIfTI_INCLUDE_DIR nifti2_io.h PATH_SUFFIXES nifti)
find_library(NIfTI_nifti2_LIBRARY nifti2)
find_library(NIfTI_znz_LIBRARY znz)
find_package(ZLIB)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(NIfTI REQUIRED_VARS NIfTI_INCLUDE_DIR NIfTI_nifti2_LIBRARY NIfTI_znz_LIBRARY ZLIB_FOUND)
if(NIfTI_FOUND AND NOT TARGET NIfTI::nifti2)
  add_library(NIfTI::nifti2 UNKNOWN IMPORTED)
  set_target_properties(NIfTI::nifti2 PROPERTIES
    IMPORTED_LOCATION "${NIfTI_nifti2_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${NIfTI_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${NIfTI_znz_LIBRARY};ZLIB::ZLIB;m")
endif()
mark_as_advanced(NIfTI_INCLUDE_DIR NIfTI_nifti2_LIBRARY NIfTI_znz_LIBRARY)
