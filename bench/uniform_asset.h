// bench/uniform_asset.h -- the global-refinement baseline of bench_render, in the
// runtime's own asset form, so the runtime's unchanged compute kernels and draws
// run it.
//
// Global refinement (paper 4.4's comparison): every face of the control mesh is
// subdivided uniformly to depth d and the finest level is drawn as triangles. In
// an lt::Asset that is:
//   levels 1..d   Refinement tables of OpenSubdiv's RefineUniform(d) topology,
//                 every vertex and edge kept (vertex points in parent-vertex order,
//                 then edge points in parent-edge order), with the baker's own Sdc
//                 masks (lt::vertexMask, lt::edgeCreaseWeight), so the edge-point
//                 and vertex-point kernels compute every vertex of every level;
//   level d       every face an IrregularFace, every (vertex, sector) a limit
//                 stencil (lt::limitStencil): the runtime's limit pass projects the
//                 finest vertices onto the limit surface with their normals and its
//                 IPP draw draws the faces as flat triangles between them;
//   levels < d    no patches and no irregular faces (nothing drawn there).
// With no regular patches the tessellator does nothing; the frame is the compute
// passes plus one plain triangle draw. Patch params carry the base face and the
// level only (origin 0): the bench renders, it never captures (u, v).
#pragma once

#include "looptess/baker.h"

#include <cstdint>

namespace ltbench {

// Element counts of a uniform asset's finest level, and the bytes a vertex-only
// global refinement would need on the GPU (see leanBytes).
struct UniformCounts {
    uint64_t faces = 0;          // triangles drawn (finest level)
    uint64_t vertices = 0;       // refined vertices, all levels (control points included)
    uint64_t refinementWords = 0;  // 32-bit words of the refinement tables (gpu_layout.h's form)
};
UniformCounts uniformCounts(const lt::Asset& uniform);

// The smallest GPU footprint of global refinement with the same kernels, without
// the limit projection: the vertex buffer (12 bytes a vertex, all levels), the
// refinement tables and a 32-bit index buffer of the finest triangles (12 bytes a
// face). A computed lower bound, not an allocation.
uint64_t leanBytes(const UniformCounts& c);

// Builds the uniform asset of `mesh` (passed lt::checkInput) at `depth` (1..8),
// with the same Sdc options and topology checks as lt::bake (holes are not drawn).
// Unsupported for boundary interpolation None on a mesh with a boundary (its
// boundary faces have no limit surface); BadInput when OpenSubdiv rejects the
// topology. The result has passed lt::validateAsset (else Internal).
lt::Status buildUniformAsset(const lt::InputMesh& mesh, int depth, lt::Asset& out);

} // namespace ltbench
