// looptess/runtime.h -- evaluates a baked asset: subdivision tables level by level,
// then every patch at the tessellator's domain points. No OpenSubdiv.
//
// This is the CPU path: it runs the same tables, in the same operation order, as
// the GPU pipeline, for tests and tools.
//
//   lt::Asset asset;                                  // from lt::readAssetGlb
//   lt::EvalSettings settings;
//   settings.tessFactor = 8;
//   lt::Tessellation soup;
//   lt::evaluateCpu(asset, asset.positions.data(), settings, soup);
//   std::vector<uint8_t> ply;
//   lt::writePly(soup, ply);
//
// Level of detail (paper 3.3): for a global factor F >= 1 the runtime depth is
// d = ceil(log2 F) capped at the asset's maximum depth. Level l < d draws its
// regular patches with factor F / 2^l (NPPs split into sub-patches whose edges
// towards level l+1 take F / 2^(l+1)) and refines its irregular faces; level d
// draws its regular patches unsplit and its irregular faces as flat triangles
// between exact limit points (IPPs). Factors are clamped to [1, 64].
#pragma once

#include "looptess/asset.h"

#include <cstdint>
#include <vector>

namespace lt {

enum class Spacing : uint8_t { Equal, FractionalOdd };

struct EvalSettings {
    float tessFactor = 1.0f;             // global factor F, >= 1
    Spacing spacing = Spacing::Equal;
};

// An unwelded triangle soup: vertex 3k, 3k+1, 3k+2 form triangle k,
// counter-clockwise seen from the side the normals point to.
struct Tessellation {
    std::vector<float> positions;        // 3 per vertex
    std::vector<float> normals;          // 3 per vertex, unit length
    std::vector<uint32_t> face;          // base triangle per vertex
    std::vector<float> uv;               // 2 per vertex: location on the base triangle
    size_t vertexCount() const { return face.size(); }
    size_t triangleCount() const { return face.size() / 3; }
};

// The runtime depth for factor F (see above).
uint32_t runtimeDepth(const Asset& asset, float tessFactor);

// Runs the refinement tables of levels 1..depth on `controlPositions` (3 floats per
// control vertex) and returns every level's vertices in `vertices` (3 floats per
// global vertex; entries of levels above `depth` are left zero). `asset` must have
// passed validateAsset; depth <= asset.maxDepth().
void subdivideCpu(const Asset& asset, const float* controlPositions, uint32_t depth,
                  std::vector<float>& vertices);

// Subdivides and evaluates every patch for `settings` into `out` (replaced).
// `controlPositions` as for subdivideCpu (usually asset.positions.data()).
void evaluateCpu(const Asset& asset, const float* controlPositions, const EvalSettings& settings,
                 Tessellation& out);

// Binary little-endian PLY: vertex x y z nx ny nz (float), face (int), u v (float),
// and one face element per triangle. `bytes` is replaced.
void writePly(const Tessellation& soup, std::vector<uint8_t>& bytes);

} // namespace lt
