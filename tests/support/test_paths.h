// Where a test finds its data and the project's tools: the build tree's paths,
// compiled in, or where set the environment's, so that a test binary moved with its
// data runs elsewhere (scripts/gpu-bundle.sh): LOOPTESS_TEST_DATA (tests/data),
// LOOPTESS_CORPUS_DIR (tests/data/corpus), LOOPBAKE_EXE, LOOPRENDER_EXE.
#pragma once

#include <cstdlib>
#include <string>

namespace lt::test {

inline std::string fromEnvironment(const char* name, const char* built) {
    const char* set = std::getenv(name);
    return set && *set ? set : built;
}
inline std::string testDataDir() { return fromEnvironment("LOOPTESS_TEST_DATA", LOOPTESS_TEST_DATA); }
inline std::string corpusDir() { return fromEnvironment("LOOPTESS_CORPUS_DIR", LOOPTESS_CORPUS_DIR); }
inline std::string loopbakeExe() { return fromEnvironment("LOOPBAKE_EXE", LOOPBAKE_EXE); }
inline std::string looprenderExe() { return fromEnvironment("LOOPRENDER_EXE", LOOPRENDER_EXE); }

}  // namespace lt::test
