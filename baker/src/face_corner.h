// Private to the baker: a face's own corner, followed down the levels.
//
// Where the limit surface has a tangent plane at a vertex, every face around it
// shares one normal (limit.cpp's stencils). Where it has none -- slits, pinches,
// cusps, non-manifold edges, sharp corners whose sector holds several faces --
// each face has its own: the limit of the normal of the face's corner triangle
// as its corner is refined (the face's descendant at the vertex, wound like it):
//
//        b                  level l face f = (v, ., .); after k more levels its
//        | .                descendant at v is (v', a, b): v' the vertex's child,
//        |   .              a and b edge points of v's edges. Both are
//        v'----a            combinations of v's level-l 1-ring.
//
// cornerWeights refines the vertex's 1-ring by itself through OpenSubdiv (a
// vertex's child and its 1-ring depend on the vertex's 1-ring alone: its faces,
// their edges' sharpness, the vertex's own), one level at a time, carrying for
// every point its weights over the level-l vertex and its neighbours, so any
// configuration OpenSubdiv refines -- non-manifold, semi-sharp, Chaikin -- comes
// out exactly.
#pragma once

#include "refine.h"

#include <vector>

namespace lt {

// Each face's corner triangle (v', a, b) as its three edges, each a combination
// of the level-l points (largest weight 1: only directions matter). Any two, in
// the order (a - v', b - v'), (a - v', b - a) or (b - v', b - a), cross to the
// triangle's normal. Which two keeps a float evaluation's digits depends on the
// shape (orient.h): at a cusp a - v' and b - v' both run along the spike's axis
// and b - a has it taken out; at a slit one edge is 2^-10 of the others.
struct CornerWeights {
    struct Triangle {
        std::vector<double> edgeA;   // a - v' over `points`
        std::vector<double> edgeB;   // b - v'
        std::vector<double> edgeAB;  // b - a
    };
    std::vector<OsdIndex> points;   // the vertex, then its neighbours (GetVertexEdges order), level l
    std::vector<OsdIndex> faces;    // the vertex's faces (GetVertexFaces order), level l
    std::vector<Triangle> corners;  // parallel to faces
    // The corner of level-l face `face`, or null when it is not the vertex's.
    const Triangle* of(OsdIndex face) const;
};

// The corners of every face around `vertex` of `level`, refined `steps` levels
// further (the ring refines the same whichever face is followed). Returns false
// when OpenSubdiv refuses the 1-ring (it accepted the mesh: an internal error).
bool cornerWeights(const Far::TopologyRefiner& refiner, int level, OsdIndex vertex, int steps, CornerWeights& out);

// The level at which a face's own corner normal is taken where the surface has a
// limit normal that its stencil cannot give (a slit: spec, "Faces without a
// tangent plane"): stencils of level l refine their corner kFaceCornerLevel - l
// levels, so every level gives the same normal. 24: as far as a float position
// can tell points apart around the vertex. At spikes (no tangent plane by
// topology) the asset's deepest level instead, the finest surface it draws.
constexpr int kFaceCornerLevel = 24;

}  // namespace lt
