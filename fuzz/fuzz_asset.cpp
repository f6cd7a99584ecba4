// fuzz/fuzz_asset.cpp -- libFuzzer target: lt::fuzz::asset (entry_points.h).
#include "entry_points.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    lt::fuzz::asset(data, size);
    return 0;
}
