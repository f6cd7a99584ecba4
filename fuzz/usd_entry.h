// fuzz/usd_entry.h -- the USD reader's untrusted-input entry point (built with
// LOOPTESS_HAVE_USD only: cmake/Usd.cmake), driven as fuzz_usd drives it; apart from
// entry_points.h so that the other fuzzers never link OpenUSD.
#pragma once

#include "looptess/status.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace lt::fuzz {

// Writes the bytes as a layer file in `dir` (layer.usdc when they begin with the
// crate magic "PXR-USDC", else layer.usda) and reads it with parseUsdScene in this
// process (UsdOptions::isolate off: a crash is the finding); on success every Loop
// mesh must pass checkInput or fail it with BadInput, and its cage's controlVertex
// must name control vertices that exist.
Status usd(const uint8_t* data, size_t size, const std::string& dir);

}  // namespace lt::fuzz
