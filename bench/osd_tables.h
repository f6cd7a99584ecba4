// bench/osd_tables.h -- what an OpenSubdiv user builds for adaptive Loop on the
// GPU, timed phase by phase and measured in bytes: the comparison side of
// bench_bake.
#pragma once

#include "looptess/tools/baker.h"

#include <cstddef>
#include <cstdint>

namespace ltbench {

// Bytes of the arrays a GPU upload of OpenSubdiv's tables needs: element count
// times element size of each array (Far's own element types: int indices, float
// weights, 8-byte Far::PatchParam). The stencil arrays are those of the final
// table (refined vertices, then the patch table's local points appended).
struct OsdBytes {
    size_t stencilSizes = 0, stencilOffsets = 0, stencilIndices = 0, stencilWeights = 0;
    size_t patchArrays = 0;    // one Osd::PatchArray descriptor per patch array
    size_t patchVertices = 0;  // control vertex indices of every patch
    size_t patchParams = 0;    // one Far::PatchParam per patch
    size_t other = 0;          // quad offsets, sharpness, valence tables (0 for Loop)
    // Varying-interpolation patch indices (3 per patch for Loop): built by default
    // (Options::generateVaryingTables) but not needed to evaluate positions, so
    // not part of total(). Reported for information.
    size_t varyingVertices = 0;
    size_t stencils() const { return stencilSizes + stencilOffsets + stencilIndices + stencilWeights; }
    size_t patches() const { return patchArrays + patchVertices + patchParams + other; }
    size_t total() const { return stencils() + patches(); }
};

// Element counts behind OsdBytes, for the analysis.
struct OsdCounts {
    uint64_t refinedVertices = 0;  // stencils for refined vertices (all levels)
    uint64_t localPoints = 0;      // patch table's local (end cap) points
    uint64_t stencilWeights = 0;   // total stencil entries (index + weight pairs)
    uint64_t regularPatches = 0;   // Loop box-spline patches
    uint64_t endCapPatches = 0;    // Gregory triangles at the isolation depth
    uint64_t patchVertexCount = 0;
};

// Wall-clock seconds of each phase of one build.
struct OsdTimes {
    double refiner = 0;   // TopologyRefinerFactory::Create + RefineAdaptive
    double stencils = 0;  // StencilTableFactory::Create (all refined vertices)
    double patches = 0;   // PatchTableFactory::Create
    double append = 0;    // StencilTableFactory::AppendLocalPointStencilTable
    double total() const { return refiner + stencils + patches + append; }
};

// Builds OpenSubdiv's tables for `mesh` (passed lt::checkInput) at isolation
// `depth`, exactly as an OpenSubdiv user would for adaptive Loop:
//   refiner:  TopologyRefinerFactory<TopologyDescriptor> with the baker's Sdc
//             options, RefineAdaptive(depth) with useInfSharpPatch (the baker's
//             own lt::buildRefiner, so both sides refine the same topology);
//   stencils: StencilTableFactory, interpolation vertex, generateOffsets,
//             generateIntermediateLevels, factorizeIntermediateLevels;
//   patches:  PatchTableFactory, isolation depth, useInfSharpPatch,
//             ENDCAP_GREGORY_BASIS (float precision);
//   append:   AppendLocalPointStencilTable(refiner, stencils, local points), as
//             OpenSubdiv's tutorials and Osd::Mesh do.
// Fills `times` and, when non-null, `bytes` and `counts` (counting is not timed).
// Returns BadInput when OpenSubdiv rejects the topology.
lt::Status buildOsdTables(const lt::InputMesh& mesh, int depth, OsdTimes& times, OsdBytes* bytes = nullptr,
                          OsdCounts* counts = nullptr);

}  // namespace ltbench
