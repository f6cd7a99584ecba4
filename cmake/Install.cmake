# cmake --install: the package, by component (cmake --install BUILD --component C).
#
#   component  libraries (looptess::<name>)   headers (include/looptess/)       needs
#   runtime    formats runtime                asset.h glb.h runtime.h           zstd, Threads
#                                             status.h version.h
#   vulkan     vulkan                         vulkan.h tools/vulkan_tools.h     Vulkan
#   baker      fileio mesh osd baker          tools/file_io.h tools/mesh.h      OpenSubdiv, TinyGLTF,
#                                             tools/triangulate.h
#                                             tools/osd.h tools/baker.h         draco, stb
#   check      osd_reference check            tools/osd_reference.h             Embree 3
#                                             tools/check.h
#   tools      bin/loopbake looprender loopcheck
#
# The engine tier is include/looptess/*.h; include/looptess/tools/ is the tool tier
# (baking, checking, OpenSubdiv), which an engine never needs. lib/cmake/looptess/
# holds looptessConfig.cmake, which finds each requested component's dependencies
# again (find_package(looptess REQUIRED COMPONENTS runtime vulkan); no component
# named: all installed), and one targets file per component: no exported target
# names an absolute path.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/looptess)
set(looptess_components runtime)
set(looptess_runtime_libraries formats runtime)
set(looptess_vulkan_libraries vulkan)
set(looptess_baker_libraries fileio mesh osd baker)
set(looptess_check_libraries osd_reference check)
if(LOOPTESS_VULKAN)
  list(APPEND looptess_components vulkan)
endif()
if(LOOPTESS_TOOLCHAIN)
  list(APPEND looptess_components baker check)
endif()

foreach(component IN LISTS looptess_components)
  list(TRANSFORM looptess_${component}_libraries PREPEND looptess_ OUTPUT_VARIABLE targets)
  install(TARGETS ${targets} EXPORT looptess_${component}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT ${component}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT looptess_${component} NAMESPACE looptess:: FILE looptess_${component}Targets.cmake
    DESTINATION ${config_dir} COMPONENT ${component})
endforeach()

# Headers: each module's include/looptess/ (and its tools/) with its component.
set(looptess_runtime_modules formats runtime)
set(looptess_vulkan_modules runtime)
set(looptess_baker_modules formats mesh osd baker)
set(looptess_check_modules check)
set(looptess_runtime_headers asset.h glb.h runtime.h status.h version.h)
set(looptess_vulkan_headers vulkan.h tools/vulkan_tools.h)
set(looptess_baker_headers tools/file_io.h tools/mesh.h tools/triangulate.h tools/osd.h tools/baker.h)
set(looptess_check_headers tools/osd_reference.h tools/check.h)
foreach(component IN LISTS looptess_components)
  foreach(header IN LISTS looptess_${component}_headers)
    set(found)
    foreach(module IN LISTS looptess_${component}_modules)
      if(EXISTS ${PROJECT_SOURCE_DIR}/${module}/include/looptess/${header})
        set(found ${PROJECT_SOURCE_DIR}/${module}/include/looptess/${header})
      endif()
    endforeach()
    if(NOT found)
      message(FATAL_ERROR "cmake/Install.cmake: no module of component ${component} has looptess/${header}")
    endif()
    get_filename_component(subdir ${header} DIRECTORY)
    install(FILES ${found} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/looptess/${subdir} COMPONENT ${component})
  endforeach()
endforeach()

if(LOOPTESS_TOOLCHAIN)
  install(TARGETS loopbake looprender loopcheck RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
  # The config finds OpenSubdiv and stb again with these modules.
  install(FILES ${PROJECT_SOURCE_DIR}/cmake/modules/FindOpenSubdiv.cmake ${PROJECT_SOURCE_DIR}/cmake/modules/Findstb.cmake
    DESTINATION ${config_dir}/modules COMPONENT baker)
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/looptessConfig.cmake.in
  ${PROJECT_BINARY_DIR}/looptessConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/looptessConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/looptessConfig.cmake ${PROJECT_BINARY_DIR}/looptessConfigVersion.cmake
  DESTINATION ${config_dir} COMPONENT runtime)
