// baker/src/hard_edges.h -- glTF hard edges as infinitely sharp creases
// (InputOptions::hardEdges, loopbake --hard-edges).
//
// A glTF exporter draws a hard edge by splitting its vertices: each side of the edge
// gets its own copy, at the same position, with the normal of its side. The readers
// weld the copies into one control vertex; this collects the normal each base face's
// corner had in its primitive and gives it back as creases:
//
//          a                    edge (a, b) with exactly two faces f and g is hard
//         /|\                   when at a or at b the corners of f and g carry
//        / | \                  normals more than kHardEdgeDegrees apart:
//       / f|g \                   n_f(a) vs n_g(a), n_f(b) vs n_g(b)
//       \  |  /                 (either end: the last edge of a hard run ends at a
//        \ | /                  vertex that is not split, as the run's other edges
//         \|/                   do not reach around it)
//          b
//
// A copy split only for a UV seam has its neighbour's normal, so a seam is not a hard
// edge. A corner without a normal (its primitive has no NORMAL, or a zero one)
// decides nothing. Boundary and non-manifold edges are skipped: Far makes them
// infinitely sharp already.
#pragma once

#include "looptess/tools/mesh.h"

#include <cstdint>
#include <vector>

namespace lt {

inline constexpr double kHardEdgeDegrees = 1.0;

// The corner normals of a mesh's base faces, kept beside InputMesh::faces while a
// reader builds it.
class HardEdges {
public:
    // Appends the normals of the next base face's three corners, in its corner order
    // (3 doubles each, any length; null: none known).
    void addFace(const double* n0, const double* n1, const double* n2);
    // Removes the faces whose `drop` flag is set, as eraseTriangles does.
    void erase(const std::vector<uint8_t>& drop);
    size_t faceCount() const { return normals_.size() / 9; }
    // Appends the hard edges of `mesh` (whose faces are the ones added, in order) to
    // mesh.creases as infinitely sharp creases (a < b, sorted by edge), skipping
    // edges that already have one. Returns how many were added.
    size_t addCreases(InputMesh& mesh) const;

private:
    std::vector<float> normals_;  // 9 per face, unit length; all 0 where unknown
};

}  // namespace lt
