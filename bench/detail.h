// bench/detail.h -- where our bytes go, for bench_bake's analysis: the written
// GLB's bytes per extension property, and estimates of what format changes
// would save. Reports only; nothing here changes the format.
#pragma once

#include "looptess/asset.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ltbench {

// One EXT_mesh_loop_subdivision property (e.g. "regularPoints") summed over levels.
struct PropertyBytes {
    std::string name;
    size_t bytes = 0;      // bufferView byteLength of its accessors
    size_t wideBytes = 0;  // of those, in accessors with 4-byte integer components
};

// Bytes per property of a GLB written by lt::writeAssetGlb, in the order the
// properties first appear in the levels; from the GLB's JSON chunk (accessors
// and bufferViews), so it measures the real file. Empty when `glb` is not a GLB
// with the extension.
std::vector<PropertyBytes> glbPropertyBytes(const std::vector<uint8_t>& glb);

// A stand-in for a zero-copy loader that validates without decoding: parses the
// GLB's JSON chunk and scans every accessor in place once (the maximum of each
// integer accessor, the finiteness of each float one) on a little-endian host.
// A lower bound for such a loader (the real rules also check CSR starts and
// per-level ranges, which are further linear scans). Returns a value that
// depends on every byte scanned; 0 when `glb` is not a GLB.
uint64_t scanGlbInPlace(const std::vector<uint8_t>& glb);

// Bytes further encodings would save on `asset`'s tables, against the format as
// written (vertex indices relative to their level, u16 where they fit). Estimates:
// alignment padding ignored. The two patch point figures are alternatives.
struct Savings {
    // Patch points stored per chunk of 64 patches as a u32 base (the chunk's
    // smallest point) and u16 offsets, u32 points for a chunk spanning 65536 or
    // more; vertices numbered as now. An encoding-only change.
    size_t chunkedPatchPoints = 0;
    // The same after renumbering each level's vertices in order of first use by
    // its patches (the refinement tables permuted to match): a change of the
    // vertex order, so of the Asset, not only of the encoding.
    size_t renumberedChunkedPatchPoints = 0;
    // Limit stencils of a vertex with a vertex point in the next level reuse
    // that point's refinement ring (same neighbours) instead of their own.
    size_t sharedLimitRings = 0;
    // chunkedPatchPoints and sharedLimitRings together (both encoding-only).
    size_t combined = 0;
};
Savings estimateSavings(const lt::Asset& asset);

}  // namespace ltbench
