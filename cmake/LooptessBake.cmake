# LooptessBake.cmake -- bake glTF scenes and OBJ meshes with loopbake as build steps.
#
#   include(LooptessBake)      # from the looptess tree, or with LOOPTESS_LOOPBAKE set
#   looptess_bake(hero_bake
#       INPUT  ${CMAKE_CURRENT_SOURCE_DIR}/hero.gltf
#       OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/hero.glb
#       OPTIONS --max-depth 5 --crease-angle 40)
#
# Adds a custom command that runs `loopbake INPUT -o OUTPUT --depfile OUTPUT.d
# OPTIONS...` and a target NAME (built by ALL) that depends on it. The depfile lists
# what loopbake read (the input, its buffer and image files, --edits and
# --displacement), so Ninja and Make (CMake 3.20+) bake again when any of them
# changes, and only then. DEPENDS adds more files or targets by hand.
#
# loopbake: the `loopbake` target when this tree builds it, else LOOPTESS_LOOPBAKE
# (a path), else `loopbake` on the PATH.
function(looptess_bake name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "INPUT;OUTPUT" "OPTIONS;DEPENDS")
  if(NOT arg_INPUT OR NOT arg_OUTPUT)
    message(FATAL_ERROR "looptess_bake(${name}): INPUT and OUTPUT are required")
  endif()
  if(TARGET loopbake)
    set(tool $<TARGET_FILE:loopbake>)
    set(tool_dep loopbake)
  elseif(LOOPTESS_LOOPBAKE)
    set(tool ${LOOPTESS_LOOPBAKE})
    set(tool_dep ${LOOPTESS_LOOPBAKE})
  else()
    find_program(LOOPTESS_LOOPBAKE loopbake REQUIRED)
    set(tool ${LOOPTESS_LOOPBAKE})
    set(tool_dep ${LOOPTESS_LOOPBAKE})
  endif()
  add_custom_command(
    OUTPUT ${arg_OUTPUT}
    COMMAND ${tool} ${arg_INPUT} -o ${arg_OUTPUT} --depfile ${arg_OUTPUT}.d ${arg_OPTIONS}
    DEPENDS ${arg_INPUT} ${tool_dep} ${arg_DEPENDS}
    DEPFILE ${arg_OUTPUT}.d
    COMMENT "loopbake ${arg_INPUT}"
    VERBATIM)
  add_custom_target(${name} ALL DEPENDS ${arg_OUTPUT})
endfunction()
