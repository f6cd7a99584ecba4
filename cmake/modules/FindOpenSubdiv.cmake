# FindOpenSubdiv.cmake -- OpenSubdiv's CPU library as the imported target
# OpenSubdiv::osdCPU. Debian's packaged OpenSubdivConfig.cmake names static libraries
# the package does not ship, so this module is used instead (CMAKE_MODULE_PATH puts it
# ahead of that config). Sets OpenSubdiv_FOUND.
find_path(OpenSubdiv_INCLUDE_DIR opensubdiv/far/topologyRefiner.h)
find_library(OpenSubdiv_osdCPU_LIBRARY osdCPU)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenSubdiv REQUIRED_VARS OpenSubdiv_osdCPU_LIBRARY OpenSubdiv_INCLUDE_DIR)
mark_as_advanced(OpenSubdiv_INCLUDE_DIR OpenSubdiv_osdCPU_LIBRARY)
if(OpenSubdiv_FOUND AND NOT TARGET OpenSubdiv::osdCPU)
  add_library(OpenSubdiv::osdCPU UNKNOWN IMPORTED)
  set_target_properties(OpenSubdiv::osdCPU PROPERTIES
    IMPORTED_LOCATION "${OpenSubdiv_osdCPU_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OpenSubdiv_INCLUDE_DIR}"
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${OpenSubdiv_INCLUDE_DIR}")
endif()
