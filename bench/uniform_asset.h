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

#include "looptess/tools/baker.h"

#include <cstdint>
#include <vector>

namespace ltbench {

// Element counts of a uniform asset's finest level, and the bytes a vertex-only
// global refinement would need on the GPU (see leanBytes).
struct UniformCounts {
    uint64_t faces = 0;            // triangles drawn (finest level)
    uint64_t vertices = 0;         // refined vertices, all levels (control points included)
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

// Global refinement in chunks, for devices whose storage buffers cannot hold the
// whole asset (lavapipe: 128 MiB; bench/README.md). A chunk is a set of base faces
// of `mesh`; its asset is the uniform refinement of the chunk's faces only:
//
//   control mesh   the chunk's faces plus every face sharing a vertex with them
//                  (their 1-ring: what Loop's limit surface over the chunk reads),
//                  the cut a boundary (None becomes EdgeOnly; only the ring's outer
//                  vertices touch it, and no kept vertex reads their points)
//   levels 1..d    the refinement tables of the vertices the chunk's frame reads,
//                  found from the finest level up: the drawn faces' vertices and
//                  their 1-rings, then each kept point's parent, ring and edge
//                  stencil (every other vertex and edge point is left out)
//   level d        the limit stencils of the drawn faces' vertices, and the chunk's
//                  faces as IPPs
//
// So each drawn vertex gets the value the whole asset gives it, and the chunks'
// drawn faces together are the whole asset's. Vertices and edge points along the
// cuts between chunks are computed once per chunk reading them (the chunking's own
// cost, measured by bench_render). Errors as buildUniformAsset; Unsupported for a
// mesh with hierarchical edits.
lt::Status buildUniformChunk(const lt::InputMesh& mesh, int depth, const std::vector<uint32_t>& chunk, lt::Asset& out);

// Splits the base faces of `mesh` into `parts` (>= 1) chunks of nearly equal face
// counts, each compact in space (recursive bisection of the face centroids across
// the longest extent), each sorted. Every face is in exactly one chunk.
std::vector<std::vector<uint32_t>> partitionFaces(const lt::InputMesh& mesh, uint32_t parts);

}  // namespace ltbench
