// Level-of-detail factors (see lod.h and looptess/runtime.h).
#include "lod.h"

namespace lt {
namespace {

constexpr double kPi = 3.14159265358979323846;

// min(max(f, 1), max(cap, 1)): the factor of an edge whose level allows `cap`.
float clampFactor(float f, float cap) { return std::min(std::max(f, 1.0f), std::max(cap, 1.0f)); }

// Distance mode: the mean control edge length seen at the bounding-box centre.
float distanceFactor(const float* positions, const std::vector<uint32_t>& faces, const Lod& lod) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, sum = 0;
    for (size_t f = 0; f < faces.size(); ++f) {
        const float* a = positions + size_t(faces[f]) * 3;
        const float* b = positions + size_t(faces[f - f % 3 + (f + 1) % 3]) * 3;
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], double(a[k]));
            hi[k] = std::max(hi[k], double(a[k]));
            d2 += (double(a[k]) - b[k]) * (double(a[k]) - b[k]);
        }
        sum += std::sqrt(d2);
    }
    if (faces.empty()) return 1.0f;
    double dist2 = 0;
    for (int k = 0; k < 3; ++k) dist2 += ((lo[k] + hi[k]) * 0.5 - lod.eye[k]) * ((lo[k] + hi[k]) * 0.5 - lod.eye[k]);
    return float(sum / double(faces.size()) * lodScale(lod) / std::max(std::sqrt(dist2), 1e-20));
}

// Screen mode: the largest edgeFactor of a control edge.
float largestEdgeFactor(const float* positions, const std::vector<uint32_t>& faces, const Lod& lod) {
    float scale = lodScale(lod), largest = 0;
    for (size_t f = 0; f < faces.size(); ++f) {
        const float* a = positions + size_t(faces[f]) * 3;
        const float* b = positions + size_t(faces[f - f % 3 + (f + 1) % 3]) * 3;
        largest = std::max(largest, edgeFactor(a, b, lod.eye, scale));
    }
    return largest;
}

}  // namespace

float lodScale(const Lod& lod) { return lod.pixelsPerUnit / lod.pixelsPerEdge; }

Lod cameraLod(LodMode mode, const float eye[3], float fovYDegrees, uint32_t imageHeight, float pixelsPerEdge) {
    Lod lod;
    lod.mode = mode;
    std::copy(eye, eye + 3, lod.eye);
    lod.pixelsPerUnit = float(double(imageHeight) / (2.0 * std::tan(double(fovYDegrees) * kPi / 360.0)));
    lod.pixelsPerEdge = pixelsPerEdge;
    return lod;
}

float lodTessFactor(const float* positions, const std::vector<uint32_t>& faces, uint32_t maxDepth, bool flatAtMaxDepth,
                    const Lod& lod, float tessFactor) {
    // F <= 2^depth, also at the baked maximum, where the deepest level's patches take
    // factor 1 as its IPPs do (flat triangles: above it the patches' edges next to
    // them would split where theirs cannot).
    const float hi = std::ldexp(1.0f, int(std::min(maxDepth, 64u)));
    if (lod.mode == LodMode::Global) return flatAtMaxDepth ? std::min(tessFactor, hi) : tessFactor;
    float f = lod.mode == LodMode::Distance ? distanceFactor(positions, faces, lod)
                                            : largestEdgeFactor(positions, faces, lod);
    return f >= 1.0f ? std::min(f, hi) : 1.0f;  // NaN (a degenerate Lod) gives 1
}

float lodTessFactor(const Asset& asset, const float* controlPositions, const EvalSettings& settings) {
    return lodTessFactor(controlPositions, asset.faces, asset.maxDepth(), flatAtMaxDepth(asset), settings.lod,
                         settings.tessFactor);
}

SplitVertexIndex::SplitVertexIndex(const Asset& asset) {
    size_t levels = asset.levels.size();
    vertexChild_.resize(levels);
    edgeChild_.resize(levels);
    for (size_t l = 0; l + 1 < levels; ++l) {
        const Refinement& r = asset.levels[l + 1].refinement;
        for (uint32_t i = 0; i < r.vertexPointCount(); ++i)
            vertexChild_[l].emplace(r.vertexParent[i], r.firstVertex + i);
        uint32_t firstEdge = r.firstVertex + r.vertexPointCount();
        for (uint32_t i = 0; i < r.edgePointCount(); ++i)
            edgeChild_[l].emplace(edgeKey(r.edgeVerts[4 * i], r.edgeVerts[4 * i + 1]), firstEdge + i);
    }
}

bool SplitVertexIndex::find(const RegularPatch& patch, uint32_t level, PatchLodVertices& out) const {
    for (int i = 0; i < 3; ++i) {
        out.corner[i] = patch.points[kPatchCorner[i]];
        out.child[i] = out.edgePoint[i] = kNoVertex;
    }
    if (level + 1 >= vertexChild_.size()) return true;  // never split
    bool complete = true;
    for (int i = 0; i < 3; ++i) {
        if (!(patch.splitMask >> i & 1)) continue;
        auto e = edgeChild_[level].find(edgeKey(out.corner[i], out.corner[(i + 1) % 3]));
        complete = complete && e != edgeChild_[level].end();
        if (e != edgeChild_[level].end()) out.edgePoint[i] = e->second;
        for (int c : {i, (i + 1) % 3}) {
            auto v = vertexChild_[level].find(out.corner[c]);
            complete = complete && v != vertexChild_[level].end();
            if (v != vertexChild_[level].end()) out.child[c] = v->second;
        }
    }
    return complete;
}

PatchFactors screenPatchFactors(const float* vertices, const PatchLodVertices& v, uint32_t level, bool split,
                                const float eye[3], float scale, float tessFactor) {
    float cap = levelFactor(tessFactor, level), capFine = levelFactor(tessFactor, level + 1);
    auto at = [&](uint32_t i) { return vertices + size_t(i) * 3; };
    PatchFactors f;
    float across = 1.0f;
    for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3;
        f.edge[i] = clampFactor(edgeFactor(at(v.corner[i]), at(v.corner[j]), eye, scale), cap);
        bool halves = split && v.edgePoint[i] != kNoVertex && v.child[i] != kNoVertex && v.child[j] != kNoVertex;
        if (halves) {
            f.half[i][0] = clampFactor(edgeFactor(at(v.child[i]), at(v.edgePoint[i]), eye, scale), capFine);
            f.half[i][1] = clampFactor(edgeFactor(at(v.edgePoint[i]), at(v.child[j]), eye, scale), capFine);
            across = std::max(across, f.half[i][0] + f.half[i][1]);
        } else {
            f.half[i][0] = f.half[i][1] = clampFactor(f.edge[i] * 0.5f, capFine);  // drawn only if incomplete tables
            across = std::max(across, f.edge[i]);
        }
    }
    f.across = across;
    f.middle = std::max(across * 0.5f, 1.0f);
    return f;
}

}  // namespace lt
