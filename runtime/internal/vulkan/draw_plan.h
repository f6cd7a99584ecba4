// Private to looptess_vulkan: which draw records to draw for a factor, in which
// batches. Pure CPU code: no Vulkan.
//
// For a global factor F the depth is d = runtimeDepth(asset, F). Levels 0 .. d-1
// draw their split record lists, level d its whole list (as lt::evaluateCpu), then
// the IPPs of level d. A batch is one vkCmdDraw of consecutive records of one list.
//
// Why batches: lavapipe renders a single draw that produces more than about 65k
// tessellated vertices wrongly and 10-100x slower (it indexes a draw's vertices with
// 16 bits; observed on Mesa 22.3). Each batch's domain points are counted exactly
// with tess_domain.h (the tessellator lavapipe uses) and kept at most
// maxPointsPerDraw. The exact counts also size the capture buffer.
//
// Screen-space LOD (lod.h): the factors come from the refined vertices, which only
// the GPU has during a frame. Every per-edge factor is at most the global factor
// F's, so the plan for F (no ScreenFactorInput) bounds every batch and is what
// frames draw with (its counts are then upper bounds). A capture reads
// the vertices back first and plans with them (exact counts, as the CPU computes).
#pragma once

#include "gpu_tables.h"
#include "looptess/runtime.h"

#include <cstdint>
#include <vector>

namespace lt {

struct DrawBatch {
    uint32_t listOffset = 0;   // the record list (push constant `base`)
    uint32_t firstRecord = 0;  // within the list
    uint32_t recordCount = 0;
    uint32_t points = 0;     // domain points the tessellator makes for these records
    uint32_t triangles = 0;  // triangles it makes of them
    uint32_t pattern = 0;    // DrawPath::Patterns: N of the records' uniform pattern; 0: tessellated
};

// Which record lists a frame of depth d draws: levels l < d their split lists, level
// d its whole list (as lt::evaluateCpu). Global factors on the pattern path draw
// every level's whole list instead (planPatternDraws).
inline const RecordList& drawnList(const GpuTables& tables, uint32_t level, uint32_t depth) {
    return level < depth ? tables.levels[level].split : tables.levels[level].whole;
}

struct DrawPlan {
    float tessFactor = 0;
    Spacing spacing = Spacing::Equal;
    DrawPath path = DrawPath::Tessellator;
    uint32_t maxPointsPerDraw = 0;
    uint32_t depth = 0;
    std::vector<DrawBatch> batches;
    uint64_t patches = 0;        // drawn 12-point patches (records)
    uint64_t points = 0;         // tessellated domain points
    uint64_t tessTriangles = 0;  // triangles out of the tessellator
    uint32_t ippTriangles = 0;   // irregular faces of level `depth`
    uint32_t ippLevel = 0;
    // DrawPath::Patterns at screen-space factors: no batches; the records of the
    // drawn lists are sorted by pattern on the GPU (pattern_sort.comp) and drawn
    // indirect, one draw per pattern.
    bool sorted = false;
    uint32_t sortChunks = 0;  // sorted: chunks of LT_SORT_CHUNK records, each of one list
    uint64_t triangles() const { return tessTriangles + ippTriangles; }
};

// Default and range of DrawPlan::maxPointsPerDraw (well under lavapipe's ~65k).
constexpr uint32_t kDefaultMaxPointsPerDraw = 32768;

// What screen-space factors are computed from: the refined vertices (3 floats per
// global vertex, as the GPU has them) and the camera (lod.h).
struct ScreenFactorInput {
    const float* vertices = nullptr;
    float eye[3] = {0, 0, 0};
    float scale = 0;
};

// Plans the draws of factor `tessFactor` (>= 1) with `spacing`: uniform factors, or
// with `screen` the screen-space factors bounded by tessFactor. maxPointsPerDraw is
// clamped to >= 1; a record with more points than that gets a batch of its own.
DrawPlan planDraws(const GpuTables& tables, uint32_t depth, float tessFactor, Spacing spacing,
                   uint32_t maxPointsPerDraw = kDefaultMaxPointsPerDraw, const ScreenFactorInput* screen = nullptr);

// Plans the draws of global factor `tessFactor` on the pattern path (patterns.h):
// every regular patch of level l <= depth whole, from the level's `whole` list, as
// an instance of the uniform pattern N_l = patternFactor(F / 2^l) (a split patch's
// halves have F / 2^(l+1) each, and 2 pow2(F / 2^(l+1)) = pow2(F / 2^l) for l below
// the depth, where F / 2^l > 1). A batch holds as many instances as keep it within
// maxPointsPerDraw points (at least one).
DrawPlan planPatternDraws(const GpuTables& tables, uint32_t depth, float tessFactor,
                          uint32_t maxPointsPerDraw = kDefaultMaxPointsPerDraw);

// Plans the draws of bound F = `tessFactor` on the pattern path at screen-space
// factors (DrawPlan::sorted): the drawn lists' records (drawnList), each with the
// pattern of its edge factors (patterns.h). Without `screen` the plan has the
// uniform factors of F, which bound every screen-space frame's; with it the counts
// are exact and `keys`, if given, gets each record's pattern key (gpu_layout.h),
// list after list: what pattern_sort.comp computes.
DrawPlan planSortedPatternDraws(const GpuTables& tables, uint32_t depth, float tessFactor,
                                const ScreenFactorInput* screen = nullptr, std::vector<uint16_t>* keys = nullptr);

// `plan` split for a capture in transform feedback sessions of at most `maxBytes`
// each (`stride` bytes a vertex, and room for one triangle more, whose writing the
// capture detects): runs of consecutive batches, each a plan of its own, the IPPs in
// the last. In order, they draw what `plan` draws. Empty when a batch or the IPPs
// alone do not fit, or the plan is sorted (one indirect draw per pattern: no runs).
std::vector<DrawPlan> captureSessions(const DrawPlan& plan, uint64_t maxBytes, uint32_t stride);

// The sort region's words for `tables` (gpu_layout.h): records and chunks of the
// largest frame, over every depth.
struct SortRegionSize {
    uint32_t records = 0, chunks = 0;
};
SortRegionSize sortRegionSize(const GpuTables& tables);

// Points of the uniform refinement pattern of n segments a side.
inline uint32_t patternPoints(uint32_t n) { return (n + 1) * (n + 2) / 2; }

// Pattern key of edge factors e[0..2] (powers of two in [1, 64]; gpu_layout.h).
uint32_t patternKey(const uint32_t e[3]);

// Every pattern's indices (pattern.vert's encoding) back to back in key order:
// pattern k is indices [first[k], first[k] + count[k]), 3 a triangle, in
// makePattern's order. Built once.
struct PatternLibrary {
    std::vector<uint16_t> indices;
    std::vector<uint32_t> first, count;
    std::vector<uint32_t> points;  // pattern k's distinct points
};
const PatternLibrary& patternLibrary();

// evaluate.comp's pattern table (gpu_layout.h's LT_PT_*): each pattern's points
// in its TessDomain's order, as grid indices, and its indices naming those points
// (laid out as PatternLibrary::indices).
std::vector<uint32_t> patternTable();

}  // namespace lt
