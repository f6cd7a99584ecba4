// PatchEvaluator (patch_evaluator.h): one patch's vertices.
//
// Sub-patches of a non-plain patch (paper Fig. 8) and their edge factors: see
// sub_patches.h; screen-space level of detail: lod.h. Both shared with the Vulkan
// path.
#include "patch_evaluator.h"

#include "displacement.h"
#include "face_attributes.h"
#include "patterns.h"
#include "sub_patches.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace lt {
namespace {

// Domain points by id (sub_patches.h): corners C0, C1, C2, then midpoints M0, M1, M2.
const float kDomain[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}};

void cross(const float a[3], const float b[3], float n[3]) {
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
}

// 2^-level exactly (std::ldexp(1.0f, -level)'s bits, level < 127), without a call per
// vertex: a patch's size in its base face's (u, v).
float inversePowerOfTwo(uint32_t level) {
    const uint32_t bits = (127u - level) << 23;
    float d;
    std::memcpy(&d, &bits, 4);
    return d;
}

}  // namespace

// The domain points and triangles of one (sub-)triangle with these factors: the
// tessellator's, or with DrawPath::Patterns the pattern of the factors rounded up to
// powers of two (patterns.h).
const TessDomain& PatchEvaluator::domain(const float outer[3], float inner) {
    const bool patterns = drawsPatterns(settings_.path);
    std::array<float, 4> key = {outer[0], outer[1], outer[2], inner};
    if (patterns)
        key = {float(patternFactor(outer[0])), float(patternFactor(outer[1])), float(patternFactor(outer[2])), -1.0f};
    auto it = cache_.domains.find(key);
    if (it != cache_.domains.end()) return it->second;
    if (cache_.domainCount > EvalCache::kMaxPoints) {  // the points' weights name the domains
        cache_.domainPoints.clear();
        cache_.domains.clear();
        cache_.domainCount = cache_.domainPointCount = 0;
    }
    TessDomain& d = cache_.domains[key];
    if (patterns) {
        const uint32_t e[3] = {uint32_t(key[0]), uint32_t(key[1]), uint32_t(key[2])};
        makePattern(e, d);
    } else {
        TessSpacing spacing = settings_.spacing == Spacing::Equal ? TessSpacing::Equal : TessSpacing::FractionalOdd;
        tessellateTriangle(outer, inner, spacing, d, TessWinding::Cw);  // Cw: counter-clockwise in (x,y)
    }
    cache_.domainCount += d.pointCount();
    return d;
}

// Tessellation coordinate (x, y, z) -> (s,t) = z A + x B + y C (the file's header).
const DomainPoints& PatchEvaluator::domainPoints(const TessDomain& d, const int corners[3]) {
    const auto key = std::make_tuple(&d, corners[0], corners[1], corners[2]);
    if (auto it = cache_.domainPoints.find(key); it != cache_.domainPoints.end()) return it->second;
    if (cache_.domainPointCount + d.pointCount() > EvalCache::kMaxPoints) {
        cache_.domainPoints.clear();
        cache_.domainPointCount = 0;
    }
    cache_.domainPointCount += d.pointCount();
    DomainPoints& out = cache_.domainPoints[key];
    const float *A = kDomain[corners[0]], *B = kDomain[corners[1]], *C = kDomain[corners[2]];
    const size_t n = d.pointCount();
    out.points.reserve(n);
    out.weights.resize(36 * n);
    for (size_t i = 0; i < n; ++i) {
        const float* tc = &d.coords[i * 3];
        const float s = tc[2] * A[0] + tc[0] * B[0] + tc[1] * C[0];
        const float t = tc[2] * A[1] + tc[0] * B[1] + tc[1] * C[1];
        out.points.push_back({s, t});
        const BoxWeights w = boxSplineWeights(s, t);
        for (int k = 0; k < 12; ++k) {
            out.weights[size_t(k) * n + i] = w.w[k];
            out.weights[size_t(12 + k) * n + i] = w.ds[k];
            out.weights[size_t(24 + k) * n + i] = w.dt[k];
        }
    }
    return out;
}

void PatchEvaluator::emit(const float pos[3], const float n[3], const float dir[3], const PatchParam& param, float s,
                          float t, const float pu[3], const float pv[3]) {
    const size_t v = vertex_++;
    const float d = inversePowerOfTwo(param.level);
    float sign = param.rotated ? -1.0f : 1.0f;
    float u = d * (float(param.ui) + sign * s), w = d * (float(param.vi) + sign * t);
    float* normal = &out_.normals[3 * v];
    detail::unitVector(n, normal);
    float h = displace_ ? sampleDisplacement(asset_, param.baseFace, u, w) : 0.0f;
    float along[3];
    if (displace_) detail::unitVector(dir, along);
    for (int k = 0; k < 3; ++k) out_.positions[3 * v + size_t(k)] = displace_ ? pos[k] + along[k] * h : pos[k];
    out_.face[v] = param.baseFace;
    out_.uv[2 * v] = u;
    out_.uv[2 * v + 1] = w;
    if (tangents_) {  // spec "Texture coordinates": linear over the base face
        detail::faceTexcoord(&asset_.faceUVs[6 * size_t(param.baseFace)], u, w, &out_.texcoords[2 * v]);
        float bu[3], bv[3];  // along the base face's u and v (scaled by 2^level)
        for (int k = 0; k < 3; ++k) {
            bu[k] = sign * pu[k];
            bv[k] = sign * pv[k];
        }
        detail::faceTangent(&asset_.faceUVs[6 * size_t(param.baseFace)], bu, bv, normal, &out_.tangents[4 * v]);
    }
    if (texcoords1_)
        detail::faceAttribute(&asset_.faceUV1s[6 * size_t(param.baseFace)], 2, u, w, &out_.texcoords1[2 * v]);
    if (colors_) detail::faceAttribute(&asset_.faceColors[12 * size_t(param.baseFace)], 4, u, w, &out_.colors[4 * v]);
}

void PatchEvaluator::loadPoints(uint32_t level, uint32_t index, float p[12][3]) const {
    const RegularPatch& patch = asset_.levels[level].regular[index];
    for (int i = 0; i < 12; ++i)
        for (int k = 0; k < 3; ++k) p[i][k] = v_[size_t(patch.points[i]) * 3 + k];
    fillPhantomPoints(patch.boundaryMask, p);
}

void PatchEvaluator::evalSource(const PointSource& src, float pos[3], float n[3]) const {
    float q[12][3], ds[3], dt[3];
    loadPoints(src.level, src.patch, q);
    const RegularPatch& patch = asset_.levels[src.level].regular[src.patch];
    evalCanonicalEdge(q, patch.points, patch.boundaryMask, src.edge, src.x, cache_.weightsAt(src.x, 0.0f), pos, ds, dt);
    cross(ds, dt, n);
}

// Rule 4: the normal of a sector's first patch at its corner.
void PatchEvaluator::evalNormalSource(uint32_t normal, float n[3]) const {
    const NormalSource& ns = plan_->normals[normal];
    float q[12][3], pos[3], du[3], dv[3];
    loadPoints(ns.level, ns.patch, q);
    evalBoxSpline(q, cache_.weightsAt(kDomain[ns.corner][0], kDomain[ns.corner][1]), pos, du, dv);
    cross(du, dv, n);
}

// Watertight rules of watertight.h for boundary point (s,t) of regular patch `index`.
void PatchEvaluator::evalWatertight(uint32_t level, uint32_t index, const float p[12][3], float s, float t,
                                    const float ownDu[3], const float ownDv[3], float pos[3], float n[3], float dir[3],
                                    float du[3], float dv[3]) const {
    const RegularPatch& patch = asset_.levels[level].regular[index];
    const WatertightLevel& wl = plan_->levels[level];
    // du, dv: the patch's own derivatives, for the tangent (shared points take their
    // position and normal from a source, not their tangent).
    std::copy(ownDu, ownDu + 3, du);
    std::copy(ownDv, ownDv + 3, dv);
    int corner = s == 0.0f ? (t == 0.0f ? 0 : t == 1.0f ? 2 : -1) : (s == 1.0f && t == 0.0f ? 1 : -1);
    if (corner >= 0) {
        const uint32_t source = wl.regularCorner[3 * index + corner];
        float* memo = &cache_.corners[6 * size_t(source)];
        if (cache_.cornerFrame[source] != cache_.frame) {
            evalSource(plan_->points[source], memo, memo + 3);
            cache_.cornerFrame[source] = cache_.frame;
        }
        std::copy(memo, memo + 3, pos);
        std::copy(memo + 3, memo + 6, n);
        std::copy(n, n + 3, dir);  // rule 5
        uint32_t sector = wl.regularNormal[3 * index + corner];
        if (sector != kNoSource) evalNormalSource(sector, n);  // rule 4
        return;
    }
    int edge = t == 0.0f ? 0 : s + t == 1.0f ? 1 : 2;
    float local = edgeLocalParameter(edge, s, t);
    float x = edgeFlipped(patch.points, edge) ? 1.0f - local : local;
    uint32_t r = wl.regularEdge[3 * index + edge];
    if (r != kNoSource) {
        const EdgeRoot& root = plan_->roots[r];
        evalSource(PointSource{root.level, root.patch, root.edge, root.offset + root.scale * x}, pos, n);
    } else {
        float ds[3], dt[3];
        evalCanonicalEdge(p, patch.points, patch.boundaryMask, edge, x, cache_.weightsAt(x, 0.0f), pos, ds, dt);
        cross(ds, dt, n);
    }
    std::copy(n, n + 3, dir);  // rule 5
    if (patch.boundaryMask & (1u << edge))
        cross(ownDu, ownDv, n);  // rule 4: the position is shared, the normal this side's
}

template <class F>
void PatchEvaluator::subDomains(uint32_t level, uint32_t index, bool split, F&& f) {
    const RegularPatch& patch = asset_.levels[level].regular[index];
    // Refinement patterns at global factors draw a split patch whole (patterns.h).
    const bool patterns = drawsPatterns(settings_.path);
    const bool wholeSplit = patterns && split && patch.splitMask && !splitIndex_;
    uint8_t splitMask = split && !wholeSplit ? patch.splitMask : 0;
    PatchFactors factors = this->factors(patch, level, split);
    SubTriangle subs[4];
    int count = subTriangles(splitMask, subs);
    for (int k = 0; k < count; ++k) {
        float outer[3], inner;
        subTriangleFactors(subs[k], factors, settings_.spacing == Spacing::FractionalOdd && !patterns, outer, inner);
        if (wholeSplit) {
            uint32_t e[3];
            wholePatchPatternFactors(factors, patch.splitMask, e);
            for (int i = 0; i < 3; ++i) outer[i] = float(e[i]);
        }
        f(domain(outer, inner), subs[k].p);
    }
}

void PatchEvaluator::countRegular(uint32_t level, uint32_t index, bool split, size_t& vertices, size_t& indices) {
    Counts* known = nullptr;
    if (!splitIndex_) {  // counts_: a first frame counts every patch, each a domain lookup
        if (counts_.size() <= level) counts_.resize(level + 1);
        const uint8_t mask = asset_.levels[level].regular[index].splitMask;
        assert(mask < 8);
        known = &counts_[level][split ? mask : 8];
        if (known->known) {
            vertices = known->vertices, indices = known->indices;
            return;
        }
    }
    const bool indexed = settings_.indexed && drawsPatterns(settings_.path);
    vertices = indices = 0;
    subDomains(level, index, split, [&](const TessDomain& d, const int*) {
        vertices += indexed ? d.pointCount() : d.triangles.size();
        indices += indexed ? d.triangles.size() : 0;
    });
    if (known) *known = {vertices, indices, true};
}

void PatchEvaluator::regular(uint32_t level, uint32_t index, bool split) {
    const RegularPatch& patch = asset_.levels[level].regular[index];
    float p[12][3];
    loadPoints(level, index, p);
    // Indexed (patterns): every point once, then the triangles' indices; else every
    // triangle's three corners, each evaluated.
    const bool indexed = settings_.indexed && drawsPatterns(settings_.path);
    subDomains(level, index, split, [&](const TessDomain& d, const int* q) {
        const DomainPoints& dp = domainPoints(d, q);
        // Every domain point once (evalBoxSplineBatch), then each emitted vertex:
        // inside the patch from those sums, on its boundary by the watertight rules.
        const size_t n = dp.size();
        batch_.resize(9 * n);
        float *bp = batch_.data(), *bu = bp + 3 * n, *bv = bp + 6 * n;
        evalBoxSplineBatch(p, dp.weights.data(), n, n, bp, bu, bv);
        if (indexed) {
            const uint32_t base = uint32_t(vertex_);
            for (uint32_t t : d.triangles) out_.indices[index_++] = base + t;
        }
        const size_t points = indexed ? d.pointCount() : d.triangles.size();
        for (size_t k = 0; k < points; ++k) {
            const uint32_t j = indexed ? uint32_t(k) : d.triangles[k];
            const float s = dp[j].s, t = dp[j].t;
            float pos[3], du[3], dv[3], n3[3], dir[3];
            for (int c = 0; c < 3; ++c) {
                pos[c] = bp[size_t(c) * n + j];
                du[c] = bu[size_t(c) * n + j];
                dv[c] = bv[size_t(c) * n + j];
            }
            if (plan_ && (s == 0.0f || t == 0.0f || s + t == 1.0f)) {
                const float ownDu[3] = {du[0], du[1], du[2]}, ownDv[3] = {dv[0], dv[1], dv[2]};
                evalWatertight(level, index, p, s, t, ownDu, ownDv, pos, n3, dir, du, dv);
            } else {
                cross(du, dv, n3);
                std::copy(n3, n3 + 3, dir);
            }
            emit(pos, n3, dir, patch.param, s, t, du, dv);
        }
    });
}

PatchFactors PatchEvaluator::factors(const RegularPatch& patch, uint32_t level, bool split) const {
    if (!splitIndex_) return levelPatchFactors(tessFactor_, level);
    PatchLodVertices lv;
    splitIndex_->find(patch, level, lv);  // incomplete tables: halves from the whole edge (lod.cpp)
    return screenPatchFactors(v_.data(), lv, level, split, settings_.lod.eye, lodScale(settings_.lod), tessFactor_);
}

// Position and tangents of limit stencil `st`; returns whether it is masked.
bool PatchEvaluator::evalStencil(const LimitStencils& ls, uint32_t st, float pos[3], float tu[3], float tv[3]) {
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
    return masked;
}

void PatchEvaluator::irregular(uint32_t levelIndex, uint32_t index) {
    static const float corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    const Level& level = asset_.levels[levelIndex];
    const IrregularFace& face = level.irregular[index];
    float corners[3][3], normals[3][3], dirs[3][3], du[3][3], dv[3][3];
    bool smooth[3];
    for (int c = 0; c < 3; ++c) {
        uint32_t st = face.corners[c];
        float pos[3], tu[3], tv[3], nrm[3], dir[3];
        bool masked = evalStencil(level.limit, st, pos, tu, tv);
        smooth[c] = tangents_ && cornerDerivatives(level.limit, face, c, tu, tv, du[c], dv[c]);
        cross(tu, tv, nrm);
        std::copy(nrm, nrm + 3, dir);
        if (plan_) {
            // Watertight rule 3: a regular patch's evaluation where one has the
            // point, else the position (and rule 5's direction) of the vertex's
            // first sector stencil; rule 4: a stencil with explicit weights keeps
            // its sector's normal.
            const WatertightLevel& wl = plan_->levels[levelIndex];
            uint32_t src = wl.stencilSource[st];
            float shared[3], sharedNormal[3];
            if (src != kNoSource) {
                evalSource(plan_->points[src], shared, sharedNormal);
                if (!masked) std::copy(sharedNormal, sharedNormal + 3, nrm);
                std::copy(shared, shared + 3, pos);
                std::copy(sharedNormal, sharedNormal + 3, dir);
            } else if (wl.stencilPosition[st] != st) {
                evalStencil(level.limit, wl.stencilPosition[st], shared, tu, tv);
                std::copy(shared, shared + 3, pos);
                cross(tu, tv, dir);
            }
            if (masked && wl.stencilNormal[st] != kNoSource) evalNormalSource(wl.stencilNormal[st], nrm);
            if (masked && wl.stencilBaseNormal[st] != kNoSource) {  // rule 4b
                float basePos[3], baseU[3], baseV[3];
                evalStencil(asset_.levels[0].limit, wl.stencilBaseNormal[st], basePos, baseU, baseV);
                cross(baseU, baseV, nrm);
            }
        }
        std::copy(pos, pos + 3, corners[c]);
        std::copy(nrm, nrm + 3, normals[c]);
        std::copy(dir, dir + 3, dirs[c]);
    }
    if (irregularIndices())  // its own three corners
        for (uint32_t c = 0; c < 3; ++c) out_.indices[index_++] = uint32_t(vertex_) + c;
    for (int c = 0; c < 3; ++c) {
        if (!smooth[c])  // the tangent's derivatives: the flat triangle's edges
            for (int k = 0; k < 3; ++k) {
                du[c][k] = corners[1][k] - corners[0][k];
                dv[c][k] = corners[2][k] - corners[0][k];
            }
        emit(corners[c], normals[c], dirs[c], face.param, corner[c][0], corner[c][1], du[c], dv[c]);
    }
}

// The partial derivatives along the IPP's s and t at its corner c, for the tangent
// (spec "Tangents"), where the corner's stencil has Loop's smooth masks: from its
// tangents, the derivative towards ring neighbour j is D_j = wTu_j Tu + wTv_j Tv
// (exact at a regular vertex; at an extraordinary one, its characteristic map's
// directions), and the lattice of the IPP's (s,t) gives
//
//     c2            corner 0:  du = D(c1),          dv = D(c2)
//     | \           corner 1:  du = -D(c0),         dv = D(c2) - D(c0)
//     |   \         corner 2:  du = D(c1) - D(c0),  dv = -D(c0)
//     c0 -- c1      D(x): from the corner towards corner x
//
// False for explicit weights, or a corner missing from the ring (the caller then
// takes the flat triangle's edges, du = c1 - c0, dv = c2 - c0).
bool PatchEvaluator::cornerDerivatives(const LimitStencils& ls, const IrregularFace& face, int c, const float tu[3],
                                       const float tv[3], float du[3], float dv[3]) {
    const uint32_t st = face.corners[c];
    if (std::binary_search(ls.masked.begin(), ls.masked.end(), st)) return false;
    const uint32_t begin = ls.start[st], n = ls.start[st + 1] - begin;
    const SmoothLimitWeights& sw = smoothLimit(n);
    float d[3][3] = {};
    for (int x = 0; x < 3; ++x) {
        if (x == c) continue;
        const uint32_t target = ls.vertex[face.corners[x]];
        uint32_t j = 0;
        while (j < n && ls.ring[begin + j] != target) ++j;
        if (j == n) return false;
        for (int k = 0; k < 3; ++k) d[x][k] = sw.tangentU[j] * tu[k] + sw.tangentV[j] * tv[k];
    }
    for (int k = 0; k < 3; ++k) {
        du[k] = c == 0 ? d[1][k] : c == 1 ? -d[0][k] : d[1][k] - d[0][k];
        dv[k] = c == 0 ? d[2][k] : c == 1 ? d[2][k] - d[0][k] : -d[0][k];
    }
    return true;
}

const SmoothLimitWeights& PatchEvaluator::smoothLimit(uint32_t valence) {
    auto it = cache_.smoothLimits.find(valence);
    if (it == cache_.smoothLimits.end())
        it = cache_.smoothLimits.emplace(valence, loopSmoothLimitWeights(valence)).first;
    return it->second;
}

}  // namespace lt
