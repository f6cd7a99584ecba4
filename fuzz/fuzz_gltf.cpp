// fuzz/fuzz_gltf.cpp -- libFuzzer target: lt::fuzz::gltf (entry_points.h) with an
// empty temporary base directory, made once and removed at exit.
#include "entry_points.h"

#include <cstdlib>
#include <string>

#include <unistd.h>

namespace {

std::string gBaseDir;

void removeBaseDir() { rmdir(gBaseDir.c_str()); }

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    char pattern[] = "/tmp/looptess-fuzz-gltf-XXXXXX";
    if (!mkdtemp(pattern)) std::abort();
    gBaseDir = pattern;
    std::atexit(removeBaseDir);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    lt::fuzz::gltf(data, size, gBaseDir);
    return 0;
}
