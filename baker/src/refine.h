// Private to the baker: OpenSubdiv's adaptive topology and the Sdc masks on it.
//
// The baker takes topology (levels, parent/child links, sharpness, rules) from
// Far::TopologyRefiner::RefineAdaptive and asks Sdc for the weights of each rule;
// it builds every table itself and never uses Far's stencil or patch tables. The
// mapping from mesh to Far and Sdc's masks are the bridge's (looptess/tools/osd.h); the
// baker's refiner and limit stencils, which tests and benchmarks compare against,
// are declared in baker_refiner.h (baker/internal).
#pragma once

#include "baker_refiner.h"
#include "looptess/tools/osd.h"

#include <opensubdiv/sdc/crease.h>

#include <memory>
#include <string>
#include <vector>

namespace lt {

// Slits on regular runs (orient.h). A vertex on exactly two infinitely sharp edges
// (boundaries included) with the crease rule and no other sharpness, one of whose
// sectors holds three faces -- the run a regular patch takes (patches.h) -- and
// whose limit stencil for that sector has degenerate tangents on `positions` (3 per
// level-0 vertex; StencilOrienter::degenerate): at a slit, where the two crease
// neighbours coincide, its crease tangent vanishes and each face has a normal of
// its own (spec, "Faces without a tangent plane"), which a box-spline patch cannot
// give. `face`: the sector's middle face, which touches neither sharp edge:
//
//        r2     r1          the sector (v; r0 .. r3), counter-clockwise; at a
//          \ f1 /           slit r0 and r3 coincide (drawn apart here)
//       f2  \  /  f0        f1 = face, the middle one
//     r3 ===== v ===== r0   ===: infinitely sharp or boundary edges
//
// `unrefined`: level 0 only. In increasing vertex order (orient.cpp).
struct SlitCorner {
    OsdIndex vertex, face;
};
std::vector<SlitCorner> slitVertices(const Far::TopologyRefiner& unrefined, const std::vector<float>& positions);

// buildRefiner marks slitVertices in face-varying channel kIsolationChannel, the
// only one the baker's refiners have: the middle face takes a value of its own at
// the vertex, so the channel is discontinuous there, and adaptive refinement
// (refineAdaptive, the channel interpolated FVAR_LINEAR_NONE) isolates the vertex
// and its vertex points like an extraordinary vertex, to the full depth. No vertex
// rule reads the channel: the surface is unchanged. The channel is also discontinuous along the
// middle face's two smooth edges at the vertex (their edge points and theirs are
// smooth-rule vertices, which OpenSubdiv does not isolate for it). True when
// `vertex` of `level` is a slit or one of its vertex points: discontinuous and on
// the crease rule. PatchFinder makes its faces irregular.
constexpr int kIsolationChannel = 0;
inline bool isolatedSlit(const Far::TopologyLevel& level, OsdIndex vertex) {
    return level.GetNumFVarChannels() > kIsolationChannel &&
           !level.DoesVertexFVarTopologyMatch(vertex, kIsolationChannel) &&
           level.GetVertexRule(vertex) == Sdc::Crease::RULE_CREASE;
}

// The levels the baker reads (docs/hierarchical-edits.md, option C). Hierarchical
// edits down to level K >= 1 need every face of levels < K available, since the
// region refined for an edit is not a Far feature; so level l comes from
//
//   l <  K : `uniform`, RefineUniform(K) of the mesh, as its level l
//   l >= K : `adaptive`, RefineAdaptive(maxDepth - K) of a copy of uniform's level K
//            (faces, sharpness, holes), as its level l - K
//
// Both number level K's vertices and faces alike. Without edits below level 0,
// K = 0 and `adaptive` is buildRefiner's refiner of the mesh itself. Refining level
// l into l + 1 reads refiner(l) at its level local(l) (and local(l) + 1).
struct Topology {
    std::unique_ptr<Far::TopologyRefiner> uniform, adaptive;
    int uniformDepth = 0;  // K

    const Far::TopologyRefiner& refiner(int l) const { return l < uniformDepth ? *uniform : *adaptive; }
    int local(int l) const { return l < uniformDepth ? l : l - uniformDepth; }
    const Far::TopologyLevel& level(int l) const { return refiner(l).GetLevel(local(l)); }
    int maxLevel() const { return uniformDepth + adaptive->GetMaxLevel(); }
    // The face of level l - 1 (l >= 1) whose child `face` of level l is, or -1.
    // Level K is adaptive's level 0, which has no parent, and uniform's level K.
    OsdIndex parentFace(int l, OsdIndex face) const {
        return (l == uniformDepth ? uniform->GetLevel(l) : level(l)).GetFaceParentFace(face);
    }
};

// Builds the Topology for `mesh` with K = uniformDepth (0 .. maxDepth). As
// buildRefiner, `beforeRefine` sees the unrefined refiner of the mesh and may lower
// maxDepth, to no less than uniformDepth.
Status buildTopology(const InputMesh& mesh, int maxDepth, int uniformDepth, const std::string& name, Topology& topology,
                     const RefineHook& beforeRefine = nullptr);

// Scales `w` so that its largest magnitude is 1 (left alone when all zero):
// tangent weights shrink with every refinement step, only their direction matters.
void rescaleWeights(std::vector<double>& w);

// False where the limit surface has no tangent plane at `vertex` of `level` for
// `face`, whatever the geometry: a non-manifold vertex other than a sheet's (a
// vertex inside an edge of three or more faces, on exactly two infinitely sharp
// edges and not infinitely sharp itself: each sheet of faces between the two edges
// is a crease sector of its own), a cone (an infinitely sharp vertex with fewer
// than two infinitely sharp edges), a lasting sharp corner (three or more
// infinitely sharp edges, or two on an infinitely sharp vertex) whose sector holds
// more than one face, a crease or boundary sector of six or more faces. Each face
// there has a normal of its own (face_corner.h).
bool tangentPlaneAt(const Far::TopologyRefiner& refiner, int level, OsdIndex vertex, OsdIndex face);

inline bool isInfSharp(const Far::TopologyLevel& level, OsdIndex edge) {
    return level.IsEdgeBoundary(edge) || level.IsEdgeInfSharp(edge);
}

// How many of `vertex`'s edges are boundary or infinitely sharp.
inline int infSharpEdges(const Far::TopologyLevel& level, OsdIndex vertex) {
    int n = 0;
    for (OsdIndex e : level.GetVertexEdges(vertex)) n += isInfSharp(level, e) ? 1 : 0;
    return n;
}

// Position of `vertex` in `face`'s vertex list, or -1.
inline int localIndex(const Far::TopologyLevel& level, OsdIndex face, OsdIndex vertex) {
    auto fv = level.GetFaceVertices(face);
    for (int i = 0; i < fv.size(); ++i)
        if (fv[i] == vertex) return i;
    return -1;
}

// The other face of a manifold `edge`, or -1.
inline OsdIndex otherFace(const Far::TopologyLevel& level, OsdIndex edge, OsdIndex face) {
    auto ef = level.GetEdgeFaces(edge);
    if (ef.size() != 2) return -1;
    return ef[0] == face ? ef[1] : ef[0];
}

}  // namespace lt
