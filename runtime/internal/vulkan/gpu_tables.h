// Private to looptess_vulkan: the asset's tables as the shaders read them (one
// uint32 buffer, laid out as shaders/gpu_layout.h describes), built on the CPU once
// per asset. Pure CPU code: no Vulkan.
//
// What the format stores as sparse sorted lists (maskedVertex, creaseEdge, masked
// limit stencils) becomes a per-output-vertex offset here, so a shader thread finds
// its weights without searching; the smooth rules' weights come from small
// per-valence tables computed with the CPU evaluator's own functions
// (subdivide_rules.h), so the GPU never evaluates cos and both paths use the same
// floats.
#pragma once

#include "lod.h"
#include "gpu_layout.h"
#include "looptess/asset.h"

#include <cstdint>
#include <vector>

namespace lt {

// Draw records of one list (gpu_layout.h's record packing), and where the list
// starts in the tables buffer (the draws' push constant `base`).
struct RecordList {
    uint32_t offset = 0;
    std::vector<uint32_t> records;
};

struct GpuLevelInfo {
    uint32_t firstVertex = 0;
    uint32_t vertexPoints = 0, edgePoints = 0;
    uint32_t stencils = 0, irregular = 0;
    uint32_t editedVertices = 0;  // threads of the level's edit pass (0: none)
    // Threads of the watertight pass at this depth (LT_L_WT_*_COUNT).
    uint32_t watertightPoints = 0, watertightNormals = 0, watertightRoots = 0;
    RecordList whole;  // one record per regular patch: drawn when the level is the depth
    RecordList split;  // NPPs cut into sub-triangles: drawn when the level is above it
};

struct GpuTables {
    std::vector<uint32_t> words;       // the tables buffer
    std::vector<GpuLevelInfo> levels;  // [0 .. maxDepth]
    uint32_t controlVertices = 0;
    uint32_t totalVertices = 0;
    uint32_t maxStencils = 0;  // largest limit stencil count of a level
    // Hierarchical edits: asset.editCount(), and the word offset of their values
    // (EDIT_VALUES, 3 floats per edit, rewritten by every recordSubdivision).
    uint32_t editCount = 0;
    uint32_t editValues = 0;
    // Words of `words` that only watertight evaluation reads (the LT_WT_* records,
    // the LT_L_LS_WT arrays) plus the patches' LT_PATCH_WT and LT_PATCH_WT_BITS words;
    // with watertightResultFloats, its memory cost.
    size_t watertightWords = 0;
    // Floats of the watertight pass's results, after LT_LIMIT_FLOATS * maxStencils in
    // the limit buffer (gpu_layout.h).
    uint64_t watertightResultFloats = 0;
    // Words of the sort region (gpu_layout.h), which only screen-space factors on
    // the pattern path use.
    size_t sortWords = 0;
    bool displaced = false;  // the asset has a displacement map
    // A boundary or sharp patch edge lies on a root edge that is neither (not in the
    // reference baker's assets): watertight draws need two box-spline evaluations
    // per point, which pipelines keep with the displacement specialization
    // (watertight.glsl, GraphicsKey::displace).
    bool smoothCreaseRoots = false;
    // Per regular patch (global index): the vertices its screen-space factors read
    // (lod.h), kept on the CPU to plan captures exactly.
    std::vector<PatchLodVertices> lodVertices;
};

// Builds the tables of `asset`, which must have passed validateAsset. Fails with
// Unsupported when the asset exceeds what the packing holds (2^23 regular patches,
// 255 levels, 2^32 words) or a split edge's finer vertices are missing.
Status buildGpuTables(const Asset& asset, GpuTables& out);

// A draw record's patch (global index) and the domain point id of its
// sub-triangle's corner i = 0, 1, 2 (A, B, C; sub_patches.h's ids).
inline uint32_t recordPatch(uint32_t record) { return record & LT_RECORD_PATCH_MASK; }
inline int recordCorner(uint32_t record, int i) { return int((record >> (LT_RECORD_PATCH_BITS + 3 * i)) & 7u); }

}  // namespace lt
