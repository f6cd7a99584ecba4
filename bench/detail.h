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
    size_t bytes = 0;       // bufferView byteLength of its accessors
    size_t wideBytes = 0;   // of those, in accessors with 4-byte integer components
};

// Bytes per property of a GLB written by lt::writeAssetGlb, in the order the
// properties first appear in the levels; from the GLB's JSON chunk (accessors
// and bufferViews), so it measures the real file. Empty when `glb` is not a GLB
// with the extension.
std::vector<PropertyBytes> glbPropertyBytes(const std::vector<uint8_t>& glb);

// Bytes each format change would save on `asset`'s tables (estimates: alignment
// padding ignored). Each is measured against the current format alone; they
// overlap (limitRings and limitWeights both touch the limit tables, the others'
// index widths), so the combined figure is computed separately.
struct Savings {
    // Every vertex index stored relative to the first vertex of the level it
    // points into (patch points and limit rings: level l; refinement: level
    // l-1), u16 wherever that level has fewer than 65536 vertices.
    size_t relativeIndices = 0;
    // Limit stencils whose weights are Loop's smooth limit masks (interior,
    // no creases: equal ring weights) store no weights: the runtime computes
    // them from the valence, as it already does for smooth vertex points.
    size_t smoothLimitWeights = 0;
    // Limit stencils of a vertex with a vertex point in the next level reuse
    // that point's refinement ring (same neighbours) instead of their own.
    size_t sharedLimitRings = 0;
    // All three together.
    size_t combined = 0;
};
Savings estimateSavings(const lt::Asset& asset);

} // namespace ltbench
