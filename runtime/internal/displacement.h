// Private to the runtime: sampling the asset's displacement map (asset.h's
// DisplacementMap; spec "Displacement map"), bitwise identical wherever two base
// faces meet. shaders/displacement.glsl is its GLSL twin: the same operations in
// the same order (this file is built with -ffp-contract=off, the shader marks them
// `precise`), so the CPU and GPU paths agree bit for bit on lavapipe.
//
// The evaluators displace a limit point along its unit normal:
//   displaced = position + unitNormal * sampleDisplacement(asset, face, u, v)
#pragma once

#include "looptess/asset.h"

#include <cstdint>

namespace lt {

// 1/65535 rounded to float (bits 0x37800080): a 16-bit unorm sample q decodes as
// q * kUnorm16 (a multiplication is correctly rounded on every Vulkan device, a
// division need not be). 65535 * kUnorm16 == 1.0f exactly.
inline constexpr float kUnorm16 = 1.52590219e-05f;

// The displacement, scale * value + bias in object units, at (u, v) on base face
// `baseFace` (OpenSubdiv's parameterization: corners 0, 1, 2 at (0,0), (1,0), (0,1)).
// 0 when the asset has no displacement map.
//
// Consistency (what watertightness needs):
//  - on a base-face edge -- exactly v == 0 (edge 0), u == 0 (edge 2) or u + v == 1
//    (edge 1) in floats -- only that edge's shared samples are read, along the
//    edge's canonical direction (from its smaller control vertex index), with the
//    parameter measured from that end: the face's own coordinate when it measures
//    from there (u from corner 0 on edge 0, v from corner 1 and u from corner 2 on
//    edge 1, v from corner 0 on edge 2), else 1 minus it. Two faces that pass the
//    same point (bitwise: 1 - x is exact for the dyadic parameters the evaluators
//    produce) get the same bits; so does every face at a corner, whose vertex
//    sample is returned exactly;
//  - inside the face: linear interpolation over the triangle of the tile's R-grid
//    that holds (u, v) (spec "Displacement map", Sampling).
// Coordinates outside the triangle are clamped: NaN or negative to 0, above 1 to 1;
// a point with u + v > 1 is read on edge 1 like one on it (a projection).
//
// `asset` must have passed validateAsset; baseFace < asset.faceCount().
float sampleDisplacement(const Asset& asset, uint32_t baseFace, float u, float v);

}  // namespace lt
