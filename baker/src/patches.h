// Private to the baker: which faces of a level are regular box-spline patches, and
// their 12 control points.
//
// A face is regular when each corner is one of:
//   smooth  -- interior, manifold, no sharpness, 6 faces and 6 edges;
//   crease  -- on exactly two infinitely sharp edges (boundaries count), no other
//              sharpness, and the run of faces between them that holds the face
//              has 3 faces;
//   corner  -- an infinitely sharp corner whose run holding the face is this face.
// Anything else (extraordinary valence, semi-sharp edges or corners, darts,
// non-manifold vertices, slits that buildRefiner isolated: refine.h) is irregular:
// refined, or drawn as an IPP at the last level.
//
// Ring of corner i of face (v0, v1, v2), counter-clockwise around v = v_i, starting
// at v_(i+1):  ring[0] = v_(i+1), ring[1] = v_(i+2), ring[2..5] the other neighbours.
// Moving counter-clockwise around v crosses a face's trailing edge (v_(i+2), v);
// clockwise crosses its leading edge (v, v_(i+1)). Ring entries 2..5 map to the
// box-spline points (see looptess/asset.h) as:
//   corner 0 (point 4): ring[2..5] -> 7, 3, 0, 1
//   corner 1 (point 5): ring[2..5] -> 1, 2, 6, 9
//   corner 2 (point 8): ring[2..5] -> 9, 11, 10, 7
#pragma once

#include "refine.h"

namespace lt {

struct PatchPoints {
    OsdIndex points[12];   // vertex indices of the level; phantoms hold points[4]
    uint8_t boundaryMask;  // as RegularPatch::boundaryMask
};

// Finds the regular patches of one level; remembers each vertex's corner kind.
class PatchFinder {
public:
    explicit PatchFinder(const Far::TopologyLevel& level);
    // True when `face` is a regular patch; then fills `out`.
    bool regular(OsdIndex face, PatchPoints& out);

private:
    const Far::TopologyLevel& level_;
    std::vector<int8_t> kind_;  // per vertex: -1 unknown, else a CornerKind
};

// The face across edge `edgeInFace` (edge i joins corners i and i+1) of `face`, or
// -1 on a boundary or non-manifold edge.
OsdIndex faceAcrossEdge(const Far::TopologyLevel& level, OsdIndex face, int edgeInFace);

}  // namespace lt
