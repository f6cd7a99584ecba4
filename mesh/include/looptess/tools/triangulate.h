// looptess/tools/triangulate.h -- splits the polygons of a control mesh into
// triangles without making a defect the polygons did not have (looptess_mesh; the
// OBJ reader's, and any reader of polygons). Plain computation, no I/O.
//
// A polygon is a cycle of corners c0 .. c(n-1), counter-clockwise seen from its front
// (the side its normal points to); a triangle keeps that winding:
//
//         c3 -------- c2          the quad's two splits:
//         |        .' |             diagonal c0-c2: (c0 c1 c2) (c0 c2 c3)
//         |     .'    |             diagonal c1-c3: (c1 c2 c3) (c1 c3 c0)
//         |  .'       |
//         c0 -------- c1          an n-gon's fan from corner k:
//                                   (ck ck+1 ck+2) (ck ck+2 ck+3) .. (ck ck-2 ck-1)
//
// A split is free of new defects when none of its diagonals is an edge of any other
// face of the mesh -- a side of another polygon, or a diagonal another polygon was
// split along before it. Then no edge gets a third face and no triangle repeats
// another in either winding (each triangle of an n-gon, n > 3, has a diagonal, and
// that edge has this polygon's two triangles only). The classic failure it avoids:
// two quads (a b c d) and (d c b e) sharing the edges b-c and c-d (c of valence 2),
// both split along b-d, give (b c d) and (d c b), a fin.
//
// Among the splits free of new defects, those whose triangles all face the polygon's
// way (their normals against the polygon's Newell normal, none of zero area relative
// to its longest edge: a non-convex polygon's outer diagonal folds it) are preferred;
// then, for a quad, the shorter diagonal (lengths within a relative 1e-6 tie, and the
// tie goes to c0-c2, the fan from c0); for an n-gon, the first fan by corner. Only
// fans from the first kMaxFanCorners corners are tried: O(n) each, so the work stays
// linear in the input.
#pragma once

#include "looptess/tools/mesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lt {

struct Triangulation {
    // 3 per triangle: face-vertex numbers, i.e. positions in `indices` (so a caller
    // carries per-corner data such as texture coordinates along), in polygon order;
    // a polygon's triangles are consecutive, a triangle of the input is itself.
    std::vector<uint32_t> corners;
    std::vector<uint32_t> polygon;  // per triangle: the polygon it came from
    // Polygons (ascending) with no split free of new defects: split anyway, with the
    // fewest diagonals that are edges of other faces (then as above). Callers warn.
    std::vector<uint32_t> unsplittable;
    // Polygons (ascending) split free of new defects but with a triangle that folds
    // or has zero area (no split of them has none). Callers may warn.
    std::vector<uint32_t> folded;
    // Vertices (ascending) of exactly one polygon, which has more than 3 corners: the
    // polygon mesh's corners that triangulation may give a second triangle
    // (keepPolygonCorners).
    std::vector<uint32_t> polygonCorners;
};

// How many corners of an n-gon a fan is tried from (the rest are not: see above).
constexpr uint32_t kMaxFanCorners = 32;

// Triangulates polygons given as `counts` (corners per polygon, in order) and
// `indices` (their vertices, concatenated; each < positions.size() / 3). Polygons are
// taken in order: a polygon's split sees every polygon's sides and the diagonals of
// the polygons before it. A polygon of fewer than 3 corners gives no triangle; one
// that repeats a vertex is split as any other, a diagonal from that vertex to itself
// counting as an edge of another face (readers clean polygons first). The
// result depends only on the input (no hashing order, no threads).
Triangulation triangulatePolygons(const std::vector<float>& positions, const std::vector<uint32_t>& counts,
                                  const std::vector<uint32_t>& indices);

// The boundary rule edge-and-corner on the polygons as authored. A DCC and USD's
// edgeAndCorner make a vertex of one polygon a corner: the surface passes through
// its control point. Loop's rule sees triangles: a quad's diagonal gives two of its
// corners a second triangle, and those would round off.
//
//     3 ------- 2      one quad: 0 1 2 3 are corners of one polygon;
//     |       / |      split, 0 and 2 have two triangles (Loop: smooth boundary
//     |     /   |      points), 1 and 3 one (Loop: corners)
//     |   /     |
//     0 ------- 1
//
// When mesh.boundary is EdgeAndCorner, appends an infinitely sharp corner
// (sharpness 10) to mesh.corners for each of `polygonCorners` (Triangulation's) that
// has no corner
// yet, so every corner of the polygons stays; a no-op under the other rules. Readers
// call it once the boundary rule is settled.
void keepPolygonCorners(const std::vector<uint32_t>& polygonCorners, InputMesh& mesh);

}  // namespace lt
