// fuzz/fuzz_scene.cpp -- libFuzzer target: lt::fuzz::scene (entry_points.h).
#include "entry_points.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    lt::fuzz::scene(data, size);
    return 0;
}
