// Regular patch detection and control point gathering (see patches.h).
#include "patches.h"

#include <opensubdiv/sdc/crease.h>

namespace lt {
namespace {

enum class CornerKind { Irregular, Smooth, Sharp };

// Smooth: interior valence 6 without sharpness. Sharp: only infinitely sharp
// edges (and an infinitely sharp or zero vertex sharpness); the run length decides.
CornerKind cornerKind(const Far::TopologyLevel& level, OsdIndex v) {
    if (level.IsVertexNonManifold(v) || isolatedSlit(level, v)) return CornerKind::Irregular;
    float vs = level.GetVertexSharpness(v);
    bool vInf = vs >= OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE;
    if (vs > 0.0f && !vInf) return CornerKind::Irregular;
    int sharp = 0;
    for (OsdIndex e : level.GetVertexEdges(v)) {
        if (isInfSharp(level, e))
            ++sharp;
        else if (level.GetEdgeSharpness(e) > 0.0f)
            return CornerKind::Irregular;
    }
    if (sharp == 0 && !vInf && !level.IsVertexBoundary(v))
        return level.GetVertexEdges(v).size() == 6 && level.GetVertexFaces(v).size() == 6 ? CornerKind::Smooth
                                                                                          : CornerKind::Irregular;
    auto rule = level.GetVertexRule(v);
    if (rule == OpenSubdiv::Sdc::Crease::RULE_CREASE && sharp == 2 && !vInf) return CornerKind::Sharp;
    if (rule == OpenSubdiv::Sdc::Crease::RULE_CORNER) return CornerKind::Sharp;
    return CornerKind::Irregular;
}

// Walks around corner `ci` of `face` in both directions without crossing an
// infinitely sharp edge; fills ring[2..5] where reached (else -1) and returns the
// number of faces in the run holding `face`.
int walkCorner(const Far::TopologyLevel& level, OsdIndex face, int ci, OsdIndex ring[6]) {
    auto fv = level.GetFaceVertices(face);
    OsdIndex v = fv[ci];
    ring[0] = fv[(ci + 1) % 3];
    ring[1] = fv[(ci + 2) % 3];
    for (int k = 2; k < 6; ++k) ring[k] = -1;
    int run = 1;
    // Counter-clockwise: cross trailing edges.
    OsdIndex f = face;
    for (int k = 2; k < 6; ++k) {
        int j = localIndex(level, f, v);
        OsdIndex e = level.GetFaceEdges(f)[(j + 2) % 3];
        if (isInfSharp(level, e)) break;
        OsdIndex g = otherFace(level, e, f);
        if (g < 0 || g == face) break;
        int jg = localIndex(level, g, v);
        ring[k] = level.GetFaceVertices(g)[(jg + 2) % 3];
        f = g;
        ++run;
    }
    if (run == 5) return 6;  // went all the way round: interior, already complete
    // Clockwise: cross leading edges.
    f = face;
    for (int k = 5; k >= 2; --k) {
        int j = localIndex(level, f, v);
        OsdIndex e = level.GetFaceEdges(f)[j];
        if (isInfSharp(level, e)) break;
        OsdIndex g = otherFace(level, e, f);
        if (g < 0 || g == face) break;
        int jg = localIndex(level, g, v);
        OsdIndex x = level.GetFaceVertices(g)[(jg + 1) % 3];
        if (ring[k] >= 0 && ring[k] != x) return -1;  // inconsistent ring
        ring[k] = x;
        f = g;
        ++run;
    }
    return run;
}

// Fast path for a smooth corner: OpenSubdiv orders a manifold vertex's faces and
// edges counter-clockwise with face k between edges k and k+1, so the ring is the
// far ends of the edges from the face's position on. False if that does not hold.
bool smoothRing(const Far::TopologyLevel& level, OsdIndex face, int ci, OsdIndex ring[6]) {
    auto fv = level.GetFaceVertices(face);
    OsdIndex v = fv[ci];
    auto faces = level.GetVertexFaces(v);
    auto edges = level.GetVertexEdges(v);
    if (faces.size() != 6 || edges.size() != 6) return false;
    int p = faces.FindIndex(face);
    if (p < 0) return false;
    for (int k = 0; k < 6; ++k) ring[k] = otherEnd(level, edges[(p + k) % 6], v);
    return ring[0] == fv[(ci + 1) % 3] && ring[1] == fv[(ci + 2) % 3];
}

const int kRingToPoint[3][4] = {{7, 3, 0, 1}, {1, 2, 6, 9}, {9, 11, 10, 7}};
const int kCornerPoint[3] = {4, 5, 8};
// Phantom points of a boundary edge / a boundary corner (see looptess/asset.h).
const int kEdgePhantoms[3][3] = {{0, 1, 2}, {6, 9, 11}, {10, 7, 3}};
const int kCornerPhantoms[3][2] = {{3, 0}, {2, 6}, {11, 10}};

}  // namespace

OsdIndex faceAcrossEdge(const Far::TopologyLevel& level, OsdIndex face, int edgeInFace) {
    return otherFace(level, level.GetFaceEdges(face)[edgeInFace], face);
}

PatchFinder::PatchFinder(const Far::TopologyLevel& level)
    : level_(level), kind_(size_t(level.GetNumVertices()), int8_t(-1)) {}

bool PatchFinder::regular(OsdIndex face, PatchPoints& out) {
    const Far::TopologyLevel& level = level_;
    auto fv = level.GetFaceVertices(face);
    auto fe = level.GetFaceEdges(face);
    if (fv.size() != 3) return false;
    // The corners' kinds first: an irregular one decides without walking any ring.
    CornerKind kinds[3];
    for (int i = 0; i < 3; ++i) {
        int8_t& known = kind_[size_t(fv[i])];
        if (known < 0) known = int8_t(cornerKind(level, fv[i]));
        kinds[i] = CornerKind(known);
        if (kinds[i] == CornerKind::Irregular) return false;
    }
    for (int i = 0; i < 12; ++i) out.points[i] = -1;
    uint8_t edgeBits = 0, cornerBits = 0;
    for (int i = 0; i < 3; ++i) {
        const CornerKind kind = kinds[i];
        OsdIndex ring[6];
        int run = kind == CornerKind::Smooth && smoothRing(level, face, i, ring) ? 6 : walkCorner(level, face, i, ring);
        if (kind == CornerKind::Smooth && run != 6) return false;
        if (kind == CornerKind::Sharp) {
            bool leading = isInfSharp(level, fe[i]), trailing = isInfSharp(level, fe[(i + 2) % 3]);
            bool creaseRule = level.GetVertexRule(fv[i]) == OpenSubdiv::Sdc::Crease::RULE_CREASE;
            if (run != (creaseRule ? 3 : 1)) return false;
            if (leading) edgeBits |= uint8_t(1u << i);
            if (!leading && !trailing) cornerBits |= uint8_t(1u << i);
        }
        out.points[kCornerPoint[i]] = fv[i];
        for (int k = 2; k < 6; ++k)
            if (ring[k] >= 0) out.points[kRingToPoint[i][k - 2]] = ring[k];
    }
    bool phantom[12] = {};
    for (int i = 0; i < 3; ++i) {
        if (edgeBits & (1u << i))
            for (int p : kEdgePhantoms[i]) phantom[p] = true;
        if (cornerBits & (1u << i))
            for (int p : kCornerPhantoms[i]) phantom[p] = true;
    }
    for (int p = 0; p < 12; ++p) {
        if (phantom[p])
            out.points[p] = fv[0];
        else if (out.points[p] < 0)
            return false;
    }
    out.boundaryMask = uint8_t(edgeBits | (cornerBits << 3));
    return true;
}

}  // namespace lt
