// Private to the baker and its tests (looptess_baker_internal): lt::bake with the
// correspondence of the baked vertices to OpenSubdiv's, for tests that compare the
// tables against OpenSubdiv and Hbr vertex by vertex.
#pragma once

#include "looptess/tools/baker.h"

#include <cstdint>
#include <vector>

namespace lt {

// What a test needs to compare a bake against OpenSubdiv: for every global
// vertex of the asset, the OpenSubdiv (level, vertex index) it corresponds to in a
// TopologyRefiner built with the same options and RefineAdaptive(maxDepth) (meshes
// without edits below level 0; with deeper edits the levels come from a uniform
// refiner to the deepest edit level and an adaptive one on top of it).
struct BakeTrace {
    std::vector<uint32_t> osdLevel, osdVertex;
    // For every global vertex of level l: corner `corner` of sub-triangle (face;
    // path), path.size() == l, in VertexEdit's child order (for Hbr comparisons).
    std::vector<uint32_t> face;
    std::vector<std::vector<uint8_t>> path;
    std::vector<uint8_t> corner;
};

// lt::bake, and with `trace` (optional) the trace of the baked asset.
Status bakeTraced(const InputMesh& mesh, const BakeSettings& settings, Asset& asset, BakeStats* stats,
                  BakeTrace* trace);

}  // namespace lt
