// fuzz/fuzz_edits.cpp -- libFuzzer target: lt::fuzz::edits (entry_points.h).
#include "entry_points.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    lt::fuzz::edits(data, size);
    return 0;
}
