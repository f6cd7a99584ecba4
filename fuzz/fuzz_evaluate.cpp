// fuzz/fuzz_evaluate.cpp -- libFuzzer target: lt::fuzz::evaluate (entry_points.h).
#include "entry_points.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    lt::fuzz::evaluate(data, size);
    return 0;
}
