// Private to looptess_vulkan: DrawPath::Compute, the surface evaluated in compute
// passes (shaders/evaluate.comp, LT_LAYOUT_DRAW) into the surface's own buffer and
// drawn from there as plain indexed triangles (shaders/compute.vert), in batches that
// fit the buffer (vulkan.h's drawBatches, recordBatch, recordDraw).
//
//   recordSubdivision   subdivide | limit [| screen: KEYS SCAN PLACE BATCHES ARGS]
//   recordBatch k       wait for draw k-1 | evaluate batch k | make it visible
//   recordDraw          drawIndexed(batch k)        (indirect at screen-space factors)
//
// The buffer (FrameSettings::computeBytes) holds one batch: V vertices of W words
// (LT_DRAW_WORDS) and 6 V indices, so any batch of at most V vertices fits (a pattern
// has fewer than 6 indices a vertex, an IPP 1):
//
//   [ V * W floats: the batch's vertices ][ 6 V uint32: its indices ]
//
// Global and distance factors: the host cuts the plan's records, in the CPU
// evaluator's order, into batches of whole records and IPP triangles
// (planComputeBatches). Screen-space factors: each record's pattern is known only on
// the GPU, so evaluate.comp cuts the frame by its outputs' place (its BATCHES kind),
// and the host records as many batches as the bound F's output needs, the ones past
// the frame's own empty.
#pragma once

#include "vulkan/draw_plan.h"

#include <cstdint>
#include <vector>

namespace lt {

// Records [first, first + records) of the list at `listOffset`, pattern n.
struct ComputeSegment {
    uint32_t listOffset = 0, first = 0, records = 0, pattern = 0;
};

// One batch of a frame at uniform factors: its records, then IPP corners
// [firstCorner, firstCorner + corners) (whole triangles), from 0 of the buffer.
struct ComputeBatch {
    std::vector<ComputeSegment> segments;
    uint32_t firstCorner = 0, corners = 0;
    uint32_t vertices = 0, indices = 0;
};

// The batches of `plan` (uniform factors, a pattern plan) in a buffer of `vertices`
// vertices and `indices` indices (at least one record's each), in output order.
std::vector<ComputeBatch> planComputeBatches(const DrawPlan& plan, uint32_t vertices, uint32_t indices);

// How many vertices a batch of the buffer holds: `bytes` for vertices of `words`
// words and 6 indices each.
inline uint32_t computeBatchVertices(uint32_t bytes, uint32_t words) { return bytes / (4 * words + 24); }

}  // namespace lt
