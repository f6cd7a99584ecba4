// Private to the runtime: view-dependent level of detail (paper 3.5; formulas in
// looptess/runtime.h). Used by the CPU evaluator, by the Vulkan path's tables and
// draw plan, and mirrored operation for operation by shaders/patch.tesc, so both
// paths pick bit-identical factors: only + - * / sqrt, min and max, in this order.
//
// Screen mode, a regular patch of level l drawn with global factor F (the bound
// lodTessFactor returns); cap(l) = F / 2^l:
//
//   edge[i]     clamp(edgeFactor(Ci, C(i+1)), 1, cap(l))      level l corners
//   half[i][0]  clamp(edgeFactor(child[i], edgePoint[i]), 1, cap(l+1))
//   half[i][1]  clamp(edgeFactor(edgePoint[i], child[i+1]), 1, cap(l+1))
//   across      max over i of (edge i split ? half[i][0] + half[i][1] : edge[i])
//   middle      max(across / 2, 1)
//
// A shared edge's two patches read the same two vertices (same global indices,
// hence the same bits) and clamp with the same level's cap, so they agree exactly.
// A split edge's halves are the edges of the finer neighbours: their level-(l+1)
// corners are the vertex points of Ci, C(i+1) and the edge point of edge i.
//
//     Ci ---------------- Mi ---------------- C(i+1)     the NPP's edge i (level l)
//     child[i] ------- edgePoint[i] ------- child[i+1]   the same points, level l+1
//
// Internal edges of a split patch are shared only by its own sub-triangles. At the
// deepest level cap = F / 2^depth <= 1, so every factor there is 1 (the IPP rule).
// Every factor is at most its global counterpart (uniformPatchFactors(cap(l),
// cap(l+1))), so a plan for the global factor F bounds the points drawn.
#pragma once

#include "looptess/runtime.h"
#include "sub_patches.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace lt {

constexpr uint32_t kNoVertex = 0xffffffffu;

// k = pixelsPerUnit / pixelsPerEdge, the constant of edgeFactor (pushed to the GPU).
float lodScale(const Lod& lod);

// edgeFactor(a, b) of runtime.h, unclamped.
inline float edgeFactor(const float a[3], const float b[3], const float eye[3], float scale) {
    float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    float len = std::sqrt(dx * dx + dy * dy + dz * dz);
    float mx = (a[0] + b[0]) * 0.5f - eye[0], my = (a[1] + b[1]) * 0.5f - eye[1], mz = (a[2] + b[2]) * 0.5f - eye[2];
    float dist = std::sqrt(mx * mx + my * my + mz * mz);
    return len * scale / std::max(dist, 1e-20f);
}

// Whether the finest level of `asset` has IPPs, which are drawn flat: then F is at
// most 2^maxDepth in Global mode too (runtime.h).
inline bool flatAtMaxDepth(const Asset& asset) {
    return !asset.levels.empty() && !asset.levels.back().irregular.empty();
}

// F for `lod` over a control mesh (runtime.h's lodTessFactor without an Asset):
// `maxDepth` and `flatAtMaxDepth` the asset's.
float lodTessFactor(const float* positions, const std::vector<uint32_t>& faces, uint32_t maxDepth, bool flatAtMaxDepth,
                    const Lod& lod, float tessFactor);

// The vertices a patch's screen-space factors read (global indices; child and
// edgePoint are kNoVertex for edges that are not split).
struct PatchLodVertices {
    uint32_t corner[3];
    uint32_t child[3];
    uint32_t edgePoint[3];
};

// Level l+1's vertex point of a level-l vertex and edge point of a level-l edge,
// looked up in the refinement tables (vertexParent, edgeVerts).
class SplitVertexIndex {
public:
    explicit SplitVertexIndex(const Asset& asset);
    // Fills `out` for `patch` of level `level`; false when a split edge's finer
    // vertices are missing from level+1's tables (never for a baker's asset).
    bool find(const RegularPatch& patch, uint32_t level, PatchLodVertices& out) const;

private:
    std::vector<std::unordered_map<uint32_t, uint32_t>> vertexChild_;  // [l]: level-l vertex -> level l+1
    std::vector<std::unordered_map<uint64_t, uint32_t>> edgeChild_;    // [l]: (min, max) -> level l+1
};

// Screen-mode factors of a patch of level `level` (see above) drawn `split` into
// sub-patches or whole; `vertices` 3 floats per global vertex.
PatchFactors screenPatchFactors(const float* vertices, const PatchLodVertices& v, uint32_t level, bool split,
                                const float eye[3], float scale, float tessFactor);

}  // namespace lt
