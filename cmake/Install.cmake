# cmake --install: what an engine or pipeline needs to build against looptess
# without its source tree, under the prefix:
#   include/looptess/*.h          the public headers of every module (include/ of
#                                 formats, runtime, baker and check; no private or
#                                 test-seam header)
#   lib/liblooptess_*.a           the static libraries
#   bin/loopbake, looprender, loopcheck
#   lib/cmake/looptess/           looptessConfig.cmake (+ version, targets)
#
# find_package(looptess) gives these imported targets (each with the dependencies
# it needs; the config finds the system packages they name):
#   looptess::formats   Asset, the GLB reader and writer (asset.h), the GLB container (glb.h)
#   looptess::fileio    file helpers of the tools (file_io.h)
#   looptess::runtime   CPU subdivision and evaluation (runtime.h); never OpenSubdiv
#   looptess::vulkan    the Vulkan path (vulkan.h; tools' blocking helpers:
#                       vulkan_tools.h): Vulkan::Vulkan
#   looptess::baker     lt::bake, OBJ/glTF readers (baker.h): OpenSubdiv, TinyGLTF, Draco
#   looptess::osd       the OpenSubdiv bridge (osd.h): an InputMesh as Far topology
#   looptess::check     loopcheck's checks (check.h, osd_reference.h): Embree
# Targets named looptess::internal_* carry link dependencies only. The
# looptess_*_internal targets are the tests' and benchmarks' and are not installed.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(looptess_public formats fileio runtime vulkan baker osd osd_reference check)
set(looptess_internal flags zstd opensubdiv shaders)
foreach(t IN LISTS looptess_public)
  set_target_properties(looptess_${t} PROPERTIES EXPORT_NAME ${t})
endforeach()
foreach(t IN LISTS looptess_internal)
  set_target_properties(looptess_${t} PROPERTIES EXPORT_NAME internal_${t})
endforeach()
list(TRANSFORM looptess_public PREPEND looptess_ OUTPUT_VARIABLE public_targets)
list(TRANSFORM looptess_internal PREPEND looptess_ OUTPUT_VARIABLE internal_targets)

install(TARGETS ${public_targets} ${internal_targets} EXPORT looptessTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS loopbake looprender loopcheck RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(module formats runtime baker baker/osd check)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/include/looptess DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/looptess)
install(EXPORT looptessTargets NAMESPACE looptess:: DESTINATION ${config_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/looptessConfig.cmake.in
  ${PROJECT_BINARY_DIR}/looptessConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/looptessConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/looptessConfig.cmake ${PROJECT_BINARY_DIR}/looptessConfigVersion.cmake
  DESTINATION ${config_dir})
