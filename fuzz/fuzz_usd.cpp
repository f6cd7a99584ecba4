// fuzz/fuzz_usd.cpp -- libFuzzer target: lt::fuzz::usd (usd_entry.h), in a
// temporary directory of its own.
#include "usd_entry.h"

#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string dir = [] {
        char tmpl[] = "/tmp/looptess_fuzz_usd_XXXXXX";
        const char* made = mkdtemp(tmpl);
        return std::string(made ? made : "/tmp");
    }();
    lt::fuzz::usd(data, size, dir);
    return 0;
}
