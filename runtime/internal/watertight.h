// Private to the runtime: watertight evaluation (paper 3.4; the spec's "Watertight
// evaluation" section). Shared by the CPU evaluator and the Vulkan path's tables;
// shaders/watertight.glsl mirrors the arithmetic operation for operation.
//
// A point that two patches share must come out of both with the same bits. Three
// rules, applied to every domain point of a regular patch:
//
// 1. Shared edges. A point on patch edge e (t = 0, s + t = 1 or s = 0) is computed
//    from the 10 control points that edge's curve depends on, gathered in a
//    canonical frame: the patch is rotated so that edge e is the 4 -> 5 edge
//    (kEdgeRotation), and if the edge's end has the smaller global index the
//    frame is turned half round (point i -> 9 - i), so the edge always runs from
//    its smaller-index vertex (x = 0) to its larger (x = 1):
//
//        7-----8-----9           the side the canonical edge has on its left
//       / \   / \   / \         .
//      /   \ /   \ /   \        .
//     3-----4=====5-----6        ===: the shared edge, 4 -> 5 = smaller -> larger
//      \   / \   / \   /        .
//       \ /   \ /   \ /         .
//        0-----1-----2           the side on its right
//
//    The neighbour across the edge gathers the same 10 points in the same order
//    (its own frame turned half round is ours), evaluates the box spline at
//    (x, 0) and takes the normal as d/dx x d/dy in that frame: same operations on
//    the same floats. The rotation keeps the orientation, so the normal points to
//    the patch's front side for both. On a boundary or infinitely sharp edge the
//    position is the cubic B-spline of the line points 3 4 5 6 alone (the phantom
//    rows differ on the two sides) and the normal is the patch's own.
//
// 2. Edges across levels (paper 3.4.2). A patch edge can lie on an edge of a
//    coarser regular patch: half of a non-plain patch's split edge, or, across an
//    infinitely sharp crease (whose sides OpenSubdiv refines independently; the
//    reference baker keeps them within one level, other writers may not), a
//    quarter or less. The curve is the same, so the fine patch evaluates it with the coarse
//    patch's points, at the coarse parameter:
//
//     a ---------------- m ---------------- b      coarse edge, x_c in [0, 1]
//     a' -------------- m                          fine edge, a' -> m, x_f in [0, 1]
//
//    a' (a vertex point) always has a smaller index than m (an edge point), so the
//    fine canonical edge runs a' -> m and x_c = x_f / 2 if a is the coarse
//    edge's start, else 1 - x_f / 2. Deeper: x_c = offset + scale * x_f with
//    scale = +-2^-k, exact in floats, as are the (s,t) of both sides' domain
//    points. Each edge's root is the coarsest patch edge it lies on (on a
//    boundary or sharp edge, whose sides gather different phantom points, the
//    first patch's of that level).
//
// 3. Corners and split midpoints. Every limit point that is a corner of a drawn
//    patch, or lies inside a root edge (born there as an edge point), has one
//    source: the canonical evaluation of a root edge at x (0 or 1 at a corner,
//    offset + scale / 2 at an edge point), the first found scanning levels coarse
//    to fine, so a vertex and its vertex points at finer levels, which have the
//    same limit, share it -- except where hierarchical edits move the limit: the
//    edited vertices of a level l and their level-l ring neighbours
//    (editedLimitVertices) start afresh at level l, with their vertex points below
//    them, instead of inheriting their parent's source. (The baker refines the
//    region around an edit to its level, so no coarser drawn patch has them; an
//    edge point among them takes no source from a coarser root edge either.)
//    Irregular faces take the source too when it is at
//    their level or coarser, and their limit stencil otherwise; a vertex with one
//    stencil per sector takes its position from the first.
//
// 4. Normals on creases. Where the patch has a boundary or infinitely sharp edge
//    through the point (boundaryMask), the position still comes from the source,
//    but the normal is one side's: at an edge point the patch's own (one patch per
//    side); at a corner the sector's, the box-spline normal at its corner of the
//    sector's first patch (levels coarse to fine). A sector is the set of corners
//    around a limit point joined across edges that are not boundary or sharp: same-
//    level neighbours, a patch and the coarser patch its edge lies on, an irregular
//    face and a regular patch sharing an edge; irregular corners with the same
//    limit stencil are one. An irregular corner whose stencil has explicit weights
//    takes its sector's normal when a regular patch of its level or coarser is in
//    it, and its stencil's otherwise.
//    4b. Normals at base vertices. An irregular corner with explicit weights and no
//    sector normal, on a base vertex (a corner of its base face), takes the normal of
//    level 0's stencil at that base face's corner: the same normal in exact
//    arithmetic (stencils of level l refine their corners to the same level, sectors
//    refine into sectors), and at every depth the same bits. A level-l stencil sums
//    level-l float points, on which a sliver face or a nearly straight ring no longer
//    shows its bend (jaco_finger_distal --crease-angle 40, face 1580: 20 degrees
//    off at depth 6; tests/data/normals/coincident.obj).
// 5. Displacement (spec "Displacement map") moves every point along a direction
//    all its patches share: the normal of its rule-1 evaluation (at a corner, of
//    its source; of an IPP-only vertex, of its first stencil), which is the
//    shading normal except on creases, where the sides' normals differ.
#pragma once

#include "box_spline.h"
#include "looptess/asset.h"

#include <cstdint>
#include <vector>

namespace lt {

constexpr uint32_t kNoSource = 0xffffffffu;

// kEdgeRotation[e][i]: the patch point that plays point i when edge e is turned
// to be the 4 -> 5 edge (edge 0: identity; edge 1: 5 -> 8; edge 2: 8 -> 4).
extern const uint8_t kEdgeRotation[3][12];

// "Evaluate edge `edge` of regular patch `patch` of `level` canonically at x."
struct PointSource {
    uint32_t level = 0, patch = 0;
    uint8_t edge = 0;
    float x = 0;  // 0, 0.5 or 1
};

// "This edge lies on `edge` of coarser patch `patch` of `level`": x_c = offset +
// scale * x_f (rule 2).
struct EdgeRoot {
    uint32_t level = 0, patch = 0;
    uint8_t edge = 0;
    float offset = 0, scale = 1;
};

struct WatertightLevel {
    std::vector<uint32_t> regularCorner;  // [3 * regular]: index into points
    std::vector<uint32_t> regularEdge;    // [3 * regular]: into roots, or kNoSource (its own)
    // Per limit stencil (the corners of irregular faces): the source of its
    // vertex's limit point (into points), or kNoSource: the stencil itself...
    std::vector<uint32_t> stencilSource;
    // ...with the position of the stencil stencilPosition[i]: the first of the
    // vertex's sector stencils (their rings differ, so their sums would).
    std::vector<uint32_t> stencilPosition;
    // Rule 4: into normals, or kNoSource (the normal of the point's source).
    std::vector<uint32_t> regularNormal;  // [3 * regular]
    std::vector<uint32_t> stencilNormal;  // [limit stencils] (kNoSource: the stencil's own)
    // Rule 4b: into level 0's limit stencils, or kNoSource (the stencil's own).
    std::vector<uint32_t> stencilBaseNormal;  // [limit stencils]
};

// "The normal of regular patch `patch` of `level` at its corner `corner`, from its
// own box spline" (rule 4).
struct NormalSource {
    uint32_t level = 0, patch = 0;
    uint8_t corner = 0;
};

struct WatertightPlan {
    std::vector<WatertightLevel> levels;  // [maxDepth + 1]
    std::vector<PointSource> points;
    std::vector<EdgeRoot> roots;
    std::vector<NormalSource> normals;
    size_t bytes() const;
};

// Global vertex indices [begin, begin + count) of level l's vertices (level 0: the
// control vertices), for arrays indexed by a vertex's place in its level.
struct VertexRange {
    uint32_t begin = 0, count = 0;
};
inline VertexRange levelRange(const Asset& asset, uint32_t l) {
    if (l == 0) return {0, asset.controlVertexCount()};
    const Refinement& r = asset.levels[l].refinement;
    return {r.firstVertex, r.vertexCount()};
}

// Builds the plan of rules 2 to 4 from an asset that passed validateAsset, its
// per-level parts on setupThreads(its corners, threads) threads. The same plan for
// every `threads`. Its levels are 0 .. `depth` (what a frame of that depth reads),
// the first levels of the whole plan bit for bit: rules 2 and 3 scan levels coarse
// to fine. An asset with masked corners gets every level, since a sector of rule 4
// may join its corners through deeper levels.
void buildWatertightPlan(const Asset& asset, WatertightPlan& plan, size_t threads = 0, uint32_t depth = ~0u);
// True if a regular patch has a boundary or infinitely sharp edge or corner, or a
// limit stencil is masked (rule 4 has sectors).
bool hasMaskedCorners(const Asset& asset);

// Regular patch corners from which the plan's per-level work is spread over threads
// (below, a phase is shorter than a thread's start on a busy machine).
inline constexpr size_t kParallelCorners = size_t(1) << 17;
// `threads` (0: one per core) for an asset of `corners` regular patch corners (3 a
// patch, all levels), or 1 below kParallelCorners.
size_t setupThreads(size_t corners, size_t threads);

// Rule 3 with hierarchical edits (watertight_edits.cpp): the level-l vertices
// whose limit point level l's edits move, increasing: the edited vertices and every
// vertex whose 1-ring (from the level's regular patches, limit stencils and the
// next level's vertex-point rings) has one, and the edited vertices' ring
// neighbours.
std::vector<uint32_t> editedLimitVertices(const Asset& asset, uint32_t level);

// Rule 4's part of the plan (watertight_sectors.cpp); buildWatertightPlan calls it,
// with `masked` = hasMaskedCorners(asset) (false: no sectors to join).
void assignCreaseNormals(const Asset& asset, WatertightPlan& plan, bool masked, size_t threads = 0);
// Rule 4b's (stencilBaseNormal); assignCreaseNormals calls it last.
void assignBaseNormals(const Asset& asset, WatertightPlan& plan);

// True if patch edge `edge` runs from the larger global index to the smaller
// (its canonical frame is turned half round).
inline bool edgeFlipped(const uint32_t points[12], int edge) {
    return points[kEdgeRotation[edge][4]] > points[kEdgeRotation[edge][5]];
}

// The parameter along patch edge `edge` (0 at corner `edge`) of a point (s,t) on it.
inline float edgeLocalParameter(int edge, float s, float t) { return edge == 0 ? s : edge == 1 ? t : 1.0f - t; }

// Rule 1: position and the canonical frame's derivatives of patch edge `edge` at
// canonical parameter x. `p`: the patch's 12 points with phantoms filled;
// `points`: its global indices; `mask`: its boundaryMask. Normal: ds x dt.
void evalCanonicalEdge(const float p[12][3], const uint32_t points[12], uint8_t mask, int edge, float x, float pos[3],
                       float ds[3], float dt[3]);
// The same with boxSplineWeights(x, 0) computed before: the same bits, for callers
// that meet the same x on many patches.
void evalCanonicalEdge(const float p[12][3], const uint32_t points[12], uint8_t mask, int edge, float x,
                       const BoxWeights& weights, float pos[3], float ds[3], float dt[3]);

}  // namespace lt
