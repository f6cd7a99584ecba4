# Hardening build options. Included by the top-level CMakeLists.txt after
# looptess_flags exists; both options default to OFF so the normal build is unchanged.
#
# LOOPTESS_SANITIZE  ASan + UBSan on our own targets (everything that links
#                    looptess_flags: libraries, tools, tests). Dependencies stay the
#                    uninstrumented Debian packages. Any UB aborts the process, so a
#                    finding fails the test that hit it. Used by `scripts/dev.sh sanitize`
#                    (clang; build dir build-asan).
# LOOPTESS_FUZZ      libFuzzer targets in fuzz/ (clang only). Our libraries get coverage
#                    instrumentation plus ASan + UBSan; see fuzz/README.md and
#                    `scripts/dev.sh fuzz SECONDS` (build dir build-fuzz).

option(LOOPTESS_SANITIZE "Build our targets with ASan + UBSan" OFF)
option(LOOPTESS_FUZZ "Build the libFuzzer targets in fuzz/ (clang only)" OFF)

set(looptess_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=undefined)

if(LOOPTESS_SANITIZE)
  # -g1: line tables only (reports keep file:line), which compiles and links faster
  # than RelWithDebInfo's full -g (the sanitizer build is a CI step, not a debugger's).
  # scripts/dev.sh builds it with clang: g++ takes about twice as long to compile our
  # libraries with ASan + UBSan at -O2, and g++ at -O1 (no small-function inlining)
  # runs the sanitizer tests about 2x slower.
  # Test sources (targets with LOOPTESS_TEST_SOURCES set, tests/CMakeLists.txt) leave
  # out UBSan's checks on every pointer use: null, alignment, object-size,
  # pointer-overflow and vptr. Under ASan, which guards those same loads and stores,
  # they make the test sources (half of this build) compile much slower
  # (CHANGELOG.md, 0.1.0, "CI"). The code under test keeps all of them.
  target_compile_options(looptess_flags INTERFACE ${looptess_sanitizers} -fno-omit-frame-pointer -g1
    $<$<BOOL:$<TARGET_PROPERTY:LOOPTESS_TEST_SOURCES>>:-fno-sanitize=null,alignment,object-size,pointer-overflow,vptr>)
  target_link_options(looptess_flags INTERFACE ${looptess_sanitizers})
endif()

if(LOOPTESS_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "LOOPTESS_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  # fuzzer-no-link: coverage for libFuzzer without its main(); the fuzz targets
  # themselves link -fsanitize=fuzzer (fuzz/CMakeLists.txt).
  target_compile_options(looptess_flags INTERFACE ${looptess_sanitizers} -fsanitize=fuzzer-no-link
    -fno-omit-frame-pointer)
  target_link_options(looptess_flags INTERFACE ${looptess_sanitizers})
endif()
