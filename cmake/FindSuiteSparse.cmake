# SPDX-License-Identifier: GPL-3.0-or-later
# Finds the SuiteSparse components that Debian 12 ships without a CMake package (SuiteSparse 5.x).
# Creates SuiteSparse::<COMPONENT> imported targets, e.g. SuiteSparse::CHOLMOD, SuiteSparse::UMFPACK.
include(FindPackageHandleStandardArgs)

find_path(SuiteSparse_INCLUDE_DIR NAMES SuiteSparse_config.h PATH_SUFFIXES suitesparse)
find_library(SuiteSparse_config_LIBRARY NAMES suitesparseconfig)

set(_ss_required_vars SuiteSparse_INCLUDE_DIR SuiteSparse_config_LIBRARY)
foreach(_comp IN LISTS SuiteSparse_FIND_COMPONENTS)
  string(TOLOWER "${_comp}" _lib)
  find_library(SuiteSparse_${_comp}_LIBRARY NAMES ${_lib})
  if(SuiteSparse_${_comp}_LIBRARY)
    set(SuiteSparse_${_comp}_FOUND TRUE)
  endif()
endforeach()

find_package_handle_standard_args(SuiteSparse
  REQUIRED_VARS ${_ss_required_vars}
  HANDLE_COMPONENTS)

if(SuiteSparse_FOUND)
  if(NOT TARGET SuiteSparse::config)
    add_library(SuiteSparse::config UNKNOWN IMPORTED)
    set_target_properties(SuiteSparse::config PROPERTIES
      IMPORTED_LOCATION "${SuiteSparse_config_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
  endif()
  foreach(_comp IN LISTS SuiteSparse_FIND_COMPONENTS)
    if(SuiteSparse_${_comp}_FOUND AND NOT TARGET SuiteSparse::${_comp})
      add_library(SuiteSparse::${_comp} UNKNOWN IMPORTED)
      set_target_properties(SuiteSparse::${_comp} PROPERTIES
        IMPORTED_LOCATION "${SuiteSparse_${_comp}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}"
        INTERFACE_LINK_LIBRARIES SuiteSparse::config)
    endif()
  endforeach()
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR SuiteSparse_config_LIBRARY)
