// fuzz/usd_entry.h -- the USD reader's untrusted-input entry point (built with
// LOOPTESS_HAVE_USD only: cmake/Usd.cmake), driven as fuzz_usd drives it; apart from
// entry_points.h so that the other fuzzers never link OpenUSD.
#pragma once

#include "looptess/status.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace lt::fuzz {

// Writes the bytes as `dir`/layer.usda and reads it with parseUsdScene in this
// process (UsdOptions::isolate off, so libFuzzer sees our code's coverage): Sdf's
// text parser, then ours -- every attribute taken from the layer, each mesh checked
// and built, the glTF scene. On success every Loop mesh must pass checkInput or fail
// it with BadInput, and its cage's controlVertex must name control vertices that
// exist. Crate bytes ("PXR-USDC" first) are skipped: Sdf's crate reader trusts the
// file's offsets and crashes within seconds of fuzzing (tests/data/usd/bad/
// crash_paths.usdc), which is why loopbake reads every layer in a child process;
// that path is tested, not fuzzed.
Status usd(const uint8_t* data, size_t size, const std::string& dir);

}  // namespace lt::fuzz
