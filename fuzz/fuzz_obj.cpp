// fuzz/fuzz_obj.cpp -- libFuzzer target: lt::fuzz::obj (entry_points.h).
#include "entry_points.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    lt::fuzz::obj(data, size);
    return 0;
}
