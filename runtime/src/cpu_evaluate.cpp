// CPU evaluation of every patch at the tessellator's domain points.
//
// Sub-patches of a non-plain patch (paper Fig. 8) and their edge factors: see
// sub_patches.h; screen-space level of detail: lod.h. Both shared with the Vulkan
// path.
//
// Tessellator convention (tess_domain.h): a sub-triangle (A, B, C) maps the
// tessellation coordinate (x, y, z) to (s,t) = z A + x B + y C, so outer[0] is
// edge C-A, outer[1] edge A-B, outer[2] edge B-C.
#include "looptess/runtime.h"

#include "box_spline.h"
#include "lod.h"
#include "sub_patches.h"
#include "subdivide_rules.h"
#include "tess_domain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>

namespace lt {
namespace {

// Domain points by id (sub_patches.h): corners C0, C1, C2, then midpoints M0, M1, M2.
const float kDomain[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}};

void cross(const float a[3], const float b[3], float n[3]) {
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
}

class Evaluator {
public:
    // `tessFactor`: F of `settings` (lodTessFactor).
    Evaluator(const Asset& asset, const std::vector<float>& vertices, const EvalSettings& settings, float tessFactor,
              Tessellation& out)
        : asset_(asset), v_(vertices), settings_(settings), tessFactor_(tessFactor), out_(out) {
        if (settings.lod.mode == LodMode::Screen) splitIndex_ = std::make_unique<SplitVertexIndex>(asset);
    }

    void regular(const RegularPatch& patch, uint32_t level, bool split);
    void irregular(const Level& level, const IrregularFace& face);

private:
    const TessDomain& domain(const float outer[3], float inner);
    const SmoothLimitWeights& smoothLimit(uint32_t valence);
    PatchFactors factors(const RegularPatch& patch, uint32_t level, bool split) const;
    void emit(const float pos[3], const float n[3], const PatchParam& param, float s, float t);

    const Asset& asset_;
    const std::vector<float>& v_;
    EvalSettings settings_;
    float tessFactor_;
    std::unique_ptr<SplitVertexIndex> splitIndex_;  // Screen mode only
    Tessellation& out_;
    std::map<std::array<float, 4>, TessDomain> domains_;
    std::map<uint32_t, SmoothLimitWeights> smoothLimits_;
};

const TessDomain& Evaluator::domain(const float outer[3], float inner) {
    std::array<float, 4> key = {outer[0], outer[1], outer[2], inner};
    auto it = domains_.find(key);
    if (it != domains_.end()) return it->second;
    TessDomain& d = domains_[key];
    TessSpacing spacing = settings_.spacing == Spacing::Equal ? TessSpacing::Equal : TessSpacing::FractionalOdd;
    tessellateTriangle(outer, inner, spacing, d, TessWinding::Cw);  // Cw: counter-clockwise in (x,y)
    return d;
}

void Evaluator::emit(const float pos[3], const float n[3], const PatchParam& param, float s, float t) {
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) {
        out_.positions.push_back(pos[k]);
        out_.normals.push_back(len > 0.0f ? n[k] / len : 0.0f);
    }
    float d = std::ldexp(1.0f, -int(param.level));
    float sign = param.rotated ? -1.0f : 1.0f;
    out_.face.push_back(param.baseFace);
    out_.uv.push_back(d * (float(param.ui) + sign * s));
    out_.uv.push_back(d * (float(param.vi) + sign * t));
}

void Evaluator::regular(const RegularPatch& patch, uint32_t level, bool split) {
    float p[12][3];
    for (int i = 0; i < 12; ++i)
        for (int k = 0; k < 3; ++k) p[i][k] = v_[size_t(patch.points[i]) * 3 + k];
    fillPhantomPoints(patch.boundaryMask, p);
    PatchFactors factors = this->factors(patch, level, split);
    SubTriangle subs[4];
    int count = subTriangles(split ? patch.splitMask : 0, subs);
    for (int k = 0; k < count; ++k) {
        const int* q = subs[k].p;
        float outer[3], inner;
        subTriangleFactors(subs[k], factors, outer, inner);
        const TessDomain& d = domain(outer, inner);
        const float *A = kDomain[q[0]], *B = kDomain[q[1]], *C = kDomain[q[2]];
        for (uint32_t index : d.triangles) {
            const float* tc = &d.coords[size_t(index) * 3];
            float s = tc[2] * A[0] + tc[0] * B[0] + tc[1] * C[0];
            float t = tc[2] * A[1] + tc[0] * B[1] + tc[1] * C[1];
            float pos[3], du[3], dv[3], n[3];
            evalBoxSpline(p, s, t, pos, du, dv);
            cross(du, dv, n);
            emit(pos, n, patch.param, s, t);
        }
    }
}

PatchFactors Evaluator::factors(const RegularPatch& patch, uint32_t level, bool split) const {
    if (!splitIndex_)
        return uniformPatchFactors(std::ldexp(tessFactor_, -int(level)), std::ldexp(tessFactor_, -int(level) - 1));
    PatchLodVertices lv;
    splitIndex_->find(patch, level, lv);  // incomplete tables: halves from the whole edge (lod.cpp)
    return screenPatchFactors(v_.data(), lv, level, split, settings_.lod.eye, lodScale(settings_.lod), tessFactor_);
}

void Evaluator::irregular(const Level& level, const IrregularFace& face) {
    static const float corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    const LimitStencils& ls = level.limit;
    for (int c = 0; c < 3; ++c) {
        uint32_t st = face.corners[c];
        uint32_t begin = ls.start[st], n = ls.start[st + 1] - begin;
        // Explicit weights for masked stencils, Loop's smooth limit masks otherwise.
        auto m = std::lower_bound(ls.masked.begin(), ls.masked.end(), st);
        bool masked = m != ls.masked.end() && *m == st;
        const float *wp = nullptr, *wu = nullptr, *wv = nullptr;
        float smoothPosition = 0;
        if (masked) {
            uint32_t at = ls.maskStart[size_t(m - ls.masked.begin())];
            wp = &ls.position[at];
            wu = &ls.tangentU[at];
            wv = &ls.tangentV[at];
        } else {
            const SmoothLimitWeights& sw = smoothLimit(n);
            smoothPosition = sw.position;
            wu = sw.tangentU.data();
            wv = sw.tangentV.data();
        }
        // Weights are affine: sum over differences from the vertex.
        const float* centre = &v_[size_t(ls.vertex[st]) * 3];
        float pos[3], tu[3], tv[3], nrm[3];
        for (int k = 0; k < 3; ++k) {
            float a = 0, b = 0, e = 0;
            for (uint32_t j = 0; j < n; ++j) {
                float x = v_[size_t(ls.ring[begin + j]) * 3 + k] - centre[k];
                a = a + (masked ? wp[j] : smoothPosition) * x;
                b = b + wu[j] * x;
                e = e + wv[j] * x;
            }
            pos[k] = centre[k] + a;
            tu[k] = b;
            tv[k] = e;
        }
        cross(tu, tv, nrm);
        emit(pos, nrm, face.param, corner[c][0], corner[c][1]);
    }
}

const SmoothLimitWeights& Evaluator::smoothLimit(uint32_t valence) {
    auto it = smoothLimits_.find(valence);
    if (it == smoothLimits_.end()) it = smoothLimits_.emplace(valence, loopSmoothLimitWeights(valence)).first;
    return it->second;
}

} // namespace

uint32_t runtimeDepth(const Asset& asset, float tessFactor) {
    uint32_t d = 0;
    while (d < asset.maxDepth() && std::ldexp(1.0f, int(d)) < tessFactor) ++d;
    return d;
}

void evaluateCpu(const Asset& asset, const float* controlPositions, const EvalSettings& settings, Tessellation& out) {
    out = Tessellation{};
    float tessFactor = lodTessFactor(asset, controlPositions, settings);
    uint32_t depth = runtimeDepth(asset, tessFactor);
    std::vector<float> vertices;
    subdivideCpu(asset, controlPositions, depth, vertices);
    Evaluator eval(asset, vertices, settings, tessFactor, out);
    for (uint32_t l = 0; l <= depth; ++l) {
        const Level& level = asset.levels[l];
        for (const RegularPatch& patch : level.regular) eval.regular(patch, l, l < depth);
        if (l == depth)
            for (const IrregularFace& face : level.irregular) eval.irregular(level, face);
    }
}

} // namespace lt
