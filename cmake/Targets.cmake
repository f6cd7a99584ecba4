# looptess_library(<name> <sources>...) -- a library of ours: looptess_<name>, with
# the in-tree ALIAS looptess::<name> (what add_subdirectory and FetchContent consumers
# link, the same name an installed package gives) and the EXPORT_NAME <name>. Our
# warnings and floating-point rules (looptess_flags) are a build-only dependency: an
# installed target names none of them.
function(looptess_library name)
  add_library(looptess_${name} ${ARGN})
  add_library(looptess::${name} ALIAS looptess_${name})
  set_target_properties(looptess_${name} PROPERTIES EXPORT_NAME ${name})
  target_link_libraries(looptess_${name} PRIVATE $<BUILD_INTERFACE:looptess_flags>)
endfunction()
