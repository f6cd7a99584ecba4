// Private to the baker: the limit stencils of one level's irregular faces, the
// corners of its IPPs (bake.cpp's fillPatches writes the regular patches).
//
// One stencil per (corner vertex, sector: a sheet of a non-manifold edge is one);
// per (vertex, face) where the surface has no tangent plane (face_corner.h, spec
// "Faces without a tangent plane"): spikes by topology at the asset's deepest level,
// slits by geometry at level 24. Stencils are in the order of their vertex's
// global index; each ring starts at its smallest global index.
#pragma once

#include "orient.h"
#include "refine.h"

#include "looptess/asset.h"

#include <cstdint>
#include <vector>

namespace lt {

// Fills `out` with the stencils of the irregular faces `faces` of level `level`
// (`global`: the level's vertex -> global index) and `corners` with 3 stencil
// indices per face, in the order of `faces`. `maxDepth`: the asset's deepest level.
// Runs on caches.size() threads (at least 1), each with its cache; the stencils
// are the same for every count. Internal when OpenSubdiv refuses a vertex's 1-ring.
Status buildCornerStencils(const Topology& topology, int level, int maxDepth, const StencilOrienter& orienter,
                           std::vector<StencilOrienter::Cache>& caches, const std::vector<uint32_t>& global,
                           const std::vector<OsdIndex>& faces, LimitStencils& out, std::vector<uint32_t>& corners);

}  // namespace lt
