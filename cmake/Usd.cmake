# USD input (usd/, looptess_usd): OpenUSD's Sdf from PyPI's pxr-sdf-dev, which
# scripts/setup-debian.sh installs into <repo>/.venv-usd (pinned, git-ignored).
#   LOOPTESS_USD=AUTO  (default) built when pxr-sdf is found; else a status line
#   LOOPTESS_USD=ON    required: configure fails without it
#   LOOPTESS_USD=OFF   not built (loopbake refuses .usd* input with a clear error)
# LOOPTESS_USD_ROOT is the site-packages folder that holds pxr-sdf/, TBB/ (default:
# the project's .venv-usd). Defines LOOPTESS_HAVE_USD and, when found:
#   LOOPTESS_USD_PLUGIN_DIR  fixed copies of Sdf's and Ar's plugInfo.json (their
#                            LibraryPath points at the wheel's missing .libs/), which
#                            looptess_usd registers itself: a user sets no variable
set(LOOPTESS_USD AUTO CACHE STRING "USD input for loopbake and loopcheck: AUTO, ON or OFF")
set_property(CACHE LOOPTESS_USD PROPERTY STRINGS AUTO ON OFF)
set(LOOPTESS_HAVE_USD OFF)
if(NOT LOOPTESS_USD STREQUAL "OFF" AND LOOPTESS_TOOLCHAIN)
  file(GLOB _usd_site "${PROJECT_SOURCE_DIR}/.venv-usd/lib/python3*/site-packages")
  set(LOOPTESS_USD_ROOT "${_usd_site}" CACHE PATH "site-packages folder holding pxr-sdf (pip install pxr-sdf-dev)")
  if(LOOPTESS_USD_ROOT AND EXISTS "${LOOPTESS_USD_ROOT}/pxr-sdf")
    # The wheels' CMake packages live at <site>/<name>/cmake/<name>/, a layout
    # find_package searches under each prefix. Their Python dependency is Debian's
    # python3 (the venv's interpreter), never another one first on PATH.
    list(APPEND CMAKE_PREFIX_PATH "${LOOPTESS_USD_ROOT}")
    if(NOT Python_EXECUTABLE AND EXISTS "${LOOPTESS_USD_ROOT}/../../../bin/python3")
      get_filename_component(Python_EXECUTABLE "${LOOPTESS_USD_ROOT}/../../../bin/python3" ABSOLUTE)
    endif()
    # pxr-sdf's libraries need their wheel's oneTBB (newer than Debian's libtbb12,
    # the same soname): a TBB_DIR cached before from Debian's (Embree's and
    # OpenSubdiv's dependency) leaves their TBB symbols unresolved at link. The
    # wheel's is what every target then gets, RPATH first at run time.
    if(EXISTS "${LOOPTESS_USD_ROOT}/TBB/cmake/TBB/TBBConfig.cmake")
      set(TBB_DIR "${LOOPTESS_USD_ROOT}/TBB/cmake/TBB" CACHE PATH "oneTBB (the USD wheels')" FORCE)
    endif()
    find_package(pxr-sdf QUIET)
    find_package(Python QUIET COMPONENTS Interpreter Development.Embed)
  endif()
  if(TARGET pxr::sdf AND TARGET Python::Python)
    set(LOOPTESS_HAVE_USD ON)
    set(LOOPTESS_USD_PLUGIN_DIR "${PROJECT_BINARY_DIR}/usd-plugins")
    foreach(_lib sdf ar)
      string(SUBSTRING "${_lib}" 0 1 _first)
      string(SUBSTRING "${_lib}" 1 -1 _rest)
      string(TOUPPER "${_first}" _first)
      file(READ "${LOOPTESS_USD_ROOT}/pxr-${_lib}/pluginfo/${_lib}/resources/plugInfo.json" _info)
      string(REGEX REPLACE "\"LibraryPath\": *\"[^\"]*\"" "\"LibraryPath\": \"${LOOPTESS_USD_ROOT}/pxr-${_lib}/lib/libPxr${_first}${_rest}.so\"" _info "${_info}")
      string(REPLACE "\"ResourcePath\": \"resources\"" "\"ResourcePath\": \"${LOOPTESS_USD_ROOT}/pxr-${_lib}/pluginfo/${_lib}/resources\"" _info "${_info}")
      # Plug tells plugins apart by their Root ("..", relative to the file): each
      # copy keeps its own, the wheel's folder.
      string(REPLACE "\"Root\": \"..\"" "\"Root\": \"${LOOPTESS_USD_ROOT}/pxr-${_lib}/pluginfo/${_lib}\"" _info "${_info}")
      file(WRITE "${LOOPTESS_USD_PLUGIN_DIR}/${_lib}/plugInfo.json" "${_info}")
    endforeach()
    message(STATUS "USD input: pxr-sdf ${pxr-sdf_VERSION} from ${LOOPTESS_USD_ROOT}")
  elseif(LOOPTESS_USD STREQUAL "ON")
    message(FATAL_ERROR "LOOPTESS_USD=ON but pxr-sdf was not found under LOOPTESS_USD_ROOT='${LOOPTESS_USD_ROOT}' "
      "(scripts/setup-debian.sh installs it into .venv-usd)")
  else()
    message(STATUS "USD input: off (pxr-sdf not found; scripts/setup-debian.sh installs it into .venv-usd)")
  endif()
endif()
