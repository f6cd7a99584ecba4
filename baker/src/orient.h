// Private to the baker: which way a limit stencil's normal points, and whether it
// has one, judged on the refined positions of the control mesh being baked.
//
// A stencil with explicit weights takes its tangents from OpenSubdiv's crease or
// corner masks; at a corner sector bounded by two infinitely sharp edges they run
// along those edges, so tu x tv points out of the surface only while the sector
// spans less than 180 degrees. A reflex sector (an L-shaped boundary corner, a
// concave corner where three creases meet on a CAD model) gets the inward normal.
// The control faces cannot tell: around an over-folded boundary fan (corner angles
// summing past 360 degrees, slivers) some of them point against the surface. The
// face's own corner, refined (face_corner.h), can: it converges to the surface.
//
// A slit -- an open mesh of patches never welded, a boundary vertex whose two
// boundary neighbours coincide -- has a zero crease tangent: its sector stencil
// has no normal, and each face gets its own (corner_stencils.cpp). Where the slit's
// sector has three faces, a run that regular patches take (patches.h), their
// box-spline normal at the vertex would be du x dv with du = 0, float noise
// (1 - cos up to 2 on tests/data/normals/slit_tip3.obj): slitVertices finds such
// vertices on the control mesh, and buildRefiner isolates them like extraordinary
// vertices (refine.h), so their faces are IPPs with stencils of their own at every
// depth.
#pragma once

#include "face_corner.h"
#include "refine.h"

#include <array>
#include <map>
#include <tuple>
#include <vector>

namespace lt {

// True when `stencil`'s tangents are zero or parallel (to 1e-6), or one cancels to
// 1e-5 of the sum of its terms' sizes, on `points` (3 per vertex of the stencil's
// level): the surface there has no tangent plane the stencil can give in float. A
// smooth stencil without weights (limitStencil's smoothWeights false) takes
// smoothLimitWeights'.
bool degenerateTangents(const std::vector<double>& points, const LimitStencil& stencil);

class StencilOrienter {
public:
    // What the orienter computes once and looks up again: one per thread (the
    // orienter itself is read only, so threads share it). A cache changes no result,
    // only how often one is computed. Cache-line aligned: the threads' caches lie
    // side by side.
    class alignas(64) Cache {
        friend class StencilOrienter;
        // degenerate's verdicts on coarser levels, by (level, vertex, sector).
        std::map<std::tuple<int, OsdIndex, OsdIndex>, bool> verdicts;
        int level = -1;
        std::map<std::pair<OsdIndex, int>, CornerWeights> corners;  // (vertex, steps) of `level`
        // cancelsInFloat's verdicts, by (birth level, vertex, face) there.
        std::map<std::tuple<int, OsdIndex, OsdIndex>, bool> cancelled;
        // drawnAgainst's corner normals, by (birth level, vertex, face) there.
        std::map<std::tuple<int, OsdIndex, OsdIndex>, std::vector<std::array<double, 3>>> drawn;
    };

    // `positions`: 3 per control vertex of the topology's level 0 (unedited: the
    // tables must not depend on edit values, which an application may change).
    StencilOrienter(const Topology& topology, const std::vector<float>& positions);

    // Negates stencil.tangentV when tu x tv, evaluated on the refined positions of
    // `level`, points against the normals of the corners of the faces of its
    // sector at the stencil's vertex, refined kOrientSteps levels (face_corner.h),
    // or 24, 48, 96 until they all point one way (they approach the limit's): the
    // sum of the cosines decides. Smooth stencils are left alone.
    void orient(int level, LimitStencil& stencil, Cache& cache) const;

    // Whether `stencil`, the limit stencil of `vertex` of `level` for the sector of
    // `face`, has no tangent plane in float: degenerateTangents, judged once on the
    // level where the vertex first appears (or its rule last changed) and
    // inherited by its vertex points.
    // Refined positions change the verdict: at a near-slit (two boundary
    // neighbours 1e-6 apart) the tangent shrinks like 2^-l and the other terms like
    // 4^-l, so a verdict taken per level flipped at some depth, and the normal at
    // the vertex changed with the tessellation factor (up to 2 degrees).
    //
    //     level 0      v ---- e        v's vertex points v', v'' inherit v's verdict;
    //     level 1      v' - e' - .     e' (born at level 1) is judged on level 1
    //     level 2      v'' . . .
    bool degenerate(int level, OsdIndex vertex, OsdIndex face, const LimitStencil& stencil, Cache& cache) const;

    // The limit stencil of `face`'s own corner at `vertex` of `level`: the
    // position weights of `shared` (the vertex's stencil for the face's sector; its
    // ring may be a part of the vertex's), as tangents two edges of the face's
    // corner triangle refined to level `cornerLevel` (face_corner.h; no further
    // than `level`): the two at its largest angle on these positions, which cross
    // with the least cancellation, tangentV negated where their cross product
    // points against the side the face is drawn on (drawnAgainst, up to
    // `drawnLevel`, the asset's deepest). Points are the vertex and the neighbours
    // with a weight. False when OpenSubdiv refuses the 1-ring.
    bool faceStencil(int level, OsdIndex vertex, OsdIndex face, int cornerLevel, int drawnLevel,
                     const LimitStencil& shared, LimitStencil& out, Cache& cache) const;

private:
    // faceStencil's corner at `cornerLevel`, as it is there.
    bool ownCorner(int level, OsdIndex vertex, OsdIndex face, int cornerLevel, int drawnLevel,
                   const LimitStencil& shared, LimitStencil& out, Cache& cache) const;
    // The level where `vertex` of `level` first appears, or where its rule last
    // changed as semi-sharp edges decayed, with its vertex and `face`'s ancestor there.
    std::tuple<int, OsdIndex, OsdIndex> birth(int level, OsdIndex vertex, OsdIndex face) const;
    // Whether `face`'s own corner at `vertex`, refined to cornerLevel, keeps under
    // kFloatCancel of its terms' sizes in a tangent (survives) on the baked points,
    // judged once on the level of its birth (vertex points inherit the verdict, so
    // every depth draws the same normal).
    bool cancelsInFloat(int level, OsdIndex vertex, OsdIndex face, int cornerLevel, int drawnLevel, Cache& cache) const;
    // A face's corner, refined (face_corner.h), and the two of its edges whose
    // cross product cancels least on these positions; null corner when refused.
    struct Pair {
        const CornerWeights* corner = nullptr;
        const std::vector<double>*u = nullptr, *v = nullptr;
    };
    Pair pair(int level, OsdIndex vertex, OsdIndex face, int steps, Cache& cache) const;
    // n = u x v of the pair on the positions of `level`; returns |u| |v|.
    double pairCross(int level, const Pair& p, double n[3]) const;
    // |u x v| / (|u| |v|) of the pair on the positions of `level`: above
    // kFloatSine its cross product survives the runtime's float sums.
    double sine(int level, const Pair& p) const;
    static constexpr double kFloatSine = 1e-4;
    // A tangent that keeps no more than this share of its terms' sizes is below
    // float resolution: nothing of it survives the runtime's float sums.
    static constexpr double kFloatCancel = 0x1p-24;
    // Whether `face`'s corner at `vertex` of `level` is drawn against `n`: its
    // corner triangle (in the face's winding), refined from the level where the
    // vertex first appears to `drawnLevel`, faces against n at more of those levels
    // than along it, or as many and the coarsest decides. Triangles with no area
    // (sine under kAreaSine) do not count.
    bool drawnAgainst(int level, OsdIndex vertex, OsdIndex face, int drawnLevel, const double n[3], Cache& cache) const;
    static constexpr double kAreaSine = 1e-9;
    // cornerWeights of `vertex` refined `steps` levels, computed once per vertex
    // of the level being baked (per cache).
    const CornerWeights* corners(int level, OsdIndex vertex, int steps, Cache& cache) const;
    // Orientation needs the sign only: the corner's normal is on its side of the
    // tangent plane long before it converges.
    static constexpr int kOrientSteps = 10;
    // Takes out of own's tangent weights their part along each of shared's
    // tangents that is zero on these positions (a slit's crease tangent: its two
    // ends coincide). On these positions own's tangents do not change, but they no
    // longer carry large weights that cancel, so a float evaluation keeps its digits.
    void removeNullTangents(int level, const LimitStencil& shared, LimitStencil& own) const;
    // sum_k w_k (P[points_k] - P[points_0]) on level `level`.
    void apply(int level, const std::vector<OsdIndex>& points, const std::vector<double>& w, double out[3]) const;

    const Topology& topology_;
    std::vector<std::vector<double>> points_;  // per level: 3 per vertex
    // Per level l >= 1: the level l - 1 vertex whose vertex point each vertex is, or
    // -1 (an edge point). Faces have theirs in Far (Topology::parentFace).
    std::vector<std::vector<OsdIndex>> parentVertex_;
};

}  // namespace lt
