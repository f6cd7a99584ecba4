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
#include "displacement.h"
#include "lod.h"
#include "patterns.h"
#include "sub_patches.h"
#include "subdivide_rules.h"
#include "tess_domain.h"
#include "watertight.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <thread>
#include <tuple>

namespace lt {

// A (sub-)triangle's domain points in the patch's (s,t), with their box-spline
// weights: the same for every patch drawn with that domain and sub-triangle, so
// made once (boxSplineWeights was half of the evaluation's time at each point).
struct DomainPoint {
    float s, t;
    BoxWeights weights;
};
struct DomainPoints {
    std::vector<DomainPoint> points;
    std::vector<float> weights;   // the same weights by kind and point (evalBoxSplineBatch)
    size_t size() const { return points.size(); }
    const DomainPoint& operator[](size_t i) const { return points[i]; }
};

// What evaluators build once and keep across frames (a CpuEvaluator holds one per
// thread): domains, their points' weights, smooth limit weights. The domains are
// those of one mode (refinement patterns, or the tessellator's spacing); a frame of
// another mode starts them afresh.
struct EvalCache {
    int mode = -1;
    std::map<std::array<float, 4>, TessDomain> domains;   // std::map: the addresses stay
    std::map<std::tuple<const TessDomain*, int, int, int>, DomainPoints> domainPoints;
    size_t domainCount = 0, domainPointCount = 0;   // points in each map
    std::map<uint32_t, SmoothLimitWeights> smoothLimits;
    // Bounded (about 10 MB each): at screen-space factors most patches have domains
    // of their own, and a moving camera makes new ones every frame.
    static constexpr size_t kMaxPoints = size_t(1) << 16;
};

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
    // `plan`: watertight sources (null: each patch evaluates alone).
    // `cache`: this evaluator's, kept by its owner across frames.
    Evaluator(const Asset& asset, const std::vector<float>& vertices, const EvalSettings& settings, float tessFactor,
              const WatertightPlan* plan, EvalCache& cache, Tessellation& out)
        : asset_(asset), v_(vertices), settings_(settings), tessFactor_(tessFactor), plan_(plan), cache_(cache),
          out_(out) {
        if (settings.lod.mode == LodMode::Screen) splitIndex_ = std::make_unique<SplitVertexIndex>(asset);
        displace_ = settings.displace && asset.displacement.present();
        tangents_ = !asset.faceUVs.empty();
        const int mode = drawsPatterns(settings.path) ? 2 : int(settings.spacing == Spacing::FractionalOdd);
        if (cache.mode != mode) {
            cache.domainPoints.clear();
            cache.domains.clear();
            cache.domainCount = cache.domainPointCount = 0;
            cache.mode = mode;
        }
    }

    // Vertices and indices a patch emits (in the order regular() and irregular() emit
    // them), for the output's sizes and each patch's place in it.
    void countRegular(uint32_t level, uint32_t index, bool split, size_t& vertices, size_t& indices);
    static constexpr size_t kIrregularVertices = 3;
    size_t irregularIndices() const { return settings_.indexed && drawsPatterns(settings_.path) ? 3 : 0; }
    // Where the next patch's vertices and indices go in `out`, which is sized for all.
    void at(size_t vertex, size_t index) { vertex_ = vertex, index_ = index; }
    void regular(uint32_t level, uint32_t index, bool split);
    void irregular(uint32_t level, uint32_t index);

private:
    const TessDomain& domain(const float outer[3], float inner);
    const DomainPoints& domainPoints(const TessDomain& d, const int corners[3]);   // valid until the next call
    // Calls f(domain, corners) for each (sub-)triangle regular patch `index` is drawn
    // as, in order, after `prepare(factors)`.
    template <class F> void subDomains(uint32_t level, uint32_t index, bool split, F&& f);
    const SmoothLimitWeights& smoothLimit(uint32_t valence);
    PatchFactors factors(const RegularPatch& patch, uint32_t level, bool split) const;
    // Emits a vertex with shading normal n, displaced along dir (the shared
    // direction of watertight.h's rule 5) when the asset has a map; pu, pv: the
    // partial derivatives along the patch's s and t, for the tangent.
    void emit(const float pos[3], const float n[3], const float dir[3], const PatchParam& param, float s, float t,
              const float pu[3], const float pv[3]);
    void loadPoints(uint32_t level, uint32_t index, float p[12][3]) const;
    bool evalStencil(const LimitStencils& ls, uint32_t st, float pos[3], float tu[3], float tv[3]);
    bool cornerDerivatives(const LimitStencils& ls, const IrregularFace& face, int c, const float tu[3],
                           const float tv[3], float du[3], float dv[3]);
    void evalSource(const PointSource& src, float pos[3], float n[3]) const;
    void evalNormalSource(uint32_t normal, float n[3]) const;
    void evalWatertight(uint32_t level, uint32_t index, const float p[12][3], float s, float t, const BoxWeights& w,
                        float pos[3], float n[3], float dir[3], float du[3], float dv[3]) const;

    const Asset& asset_;
    const std::vector<float>& v_;
    EvalSettings settings_;
    float tessFactor_;
    const WatertightPlan* plan_;
    EvalCache& cache_;
    bool displace_ = false;
    bool tangents_ = false;  // the asset has TEXCOORD_0
    std::unique_ptr<SplitVertexIndex> splitIndex_;  // Screen mode only
    Tessellation& out_;
    size_t vertex_ = 0, index_ = 0;   // where the next vertex and index go in out_
    std::vector<float> batch_;        // regular(): one domain's positions and derivatives
};

// The domain points and triangles of one (sub-)triangle with these factors: the
// tessellator's, or with DrawPath::Patterns the pattern of the factors rounded up to
// powers of two (patterns.h).
const TessDomain& Evaluator::domain(const float outer[3], float inner) {
    const bool patterns = drawsPatterns(settings_.path);
    std::array<float, 4> key = {outer[0], outer[1], outer[2], inner};
    if (patterns) key = {float(patternFactor(outer[0])), float(patternFactor(outer[1])), float(patternFactor(outer[2])), -1.0f};
    auto it = cache_.domains.find(key);
    if (it != cache_.domains.end()) return it->second;
    if (cache_.domainCount > EvalCache::kMaxPoints) {   // the points' weights name the domains
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
const DomainPoints& Evaluator::domainPoints(const TessDomain& d, const int corners[3]) {
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
        out.points.push_back({s, t, boxSplineWeights(s, t)});
        const BoxWeights& w = out.points.back().weights;
        for (int k = 0; k < 12; ++k) {
            out.weights[size_t(k) * n + i] = w.w[k];
            out.weights[size_t(12 + k) * n + i] = w.ds[k];
            out.weights[size_t(24 + k) * n + i] = w.dt[k];
        }
    }
    return out;
}

// a / |a| as the shaders' unitNormal: sqrt and / are correctly rounded, no rsqrt.
void unit(const float a[3], float out[3]) {
    float len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; ++k) out[k] = len > 0.0f ? a[k] / len : 0.0f;
}

void Evaluator::emit(const float pos[3], const float n[3], const float dir[3], const PatchParam& param, float s,
                     float t, const float pu[3], const float pv[3]) {
    const size_t v = vertex_++;
    float d = std::ldexp(1.0f, -int(param.level));
    float sign = param.rotated ? -1.0f : 1.0f;
    float u = d * (float(param.ui) + sign * s), w = d * (float(param.vi) + sign * t);
    float* normal = &out_.normals[3 * v];
    unit(n, normal);
    float h = displace_ ? sampleDisplacement(asset_, param.baseFace, u, w) : 0.0f;
    float along[3];
    if (displace_) unit(dir, along);
    for (int k = 0; k < 3; ++k) out_.positions[3 * v + size_t(k)] = displace_ ? pos[k] + along[k] * h : pos[k];
    out_.face[v] = param.baseFace;
    out_.uv[2 * v] = u;
    out_.uv[2 * v + 1] = w;
    if (!asset_.faceUVs.empty()) {   // spec "Texture coordinates": linear over the base face
        faceTexcoord(&asset_.faceUVs[6 * size_t(param.baseFace)], u, w, &out_.texcoords[2 * v]);
        float bu[3], bv[3];  // along the base face's u and v (scaled by 2^level)
        for (int k = 0; k < 3; ++k) {
            bu[k] = sign * pu[k];
            bv[k] = sign * pv[k];
        }
        faceTangent(&asset_.faceUVs[6 * size_t(param.baseFace)], bu, bv, normal, &out_.tangents[4 * v]);
    }
    if (!asset_.faceUV1s.empty())
        faceAttribute(&asset_.faceUV1s[6 * size_t(param.baseFace)], 2, u, w, &out_.texcoords1[2 * v]);
    if (!asset_.faceColors.empty())
        faceAttribute(&asset_.faceColors[12 * size_t(param.baseFace)], 4, u, w, &out_.colors[4 * v]);
}

void Evaluator::loadPoints(uint32_t level, uint32_t index, float p[12][3]) const {
    const RegularPatch& patch = asset_.levels[level].regular[index];
    for (int i = 0; i < 12; ++i)
        for (int k = 0; k < 3; ++k) p[i][k] = v_[size_t(patch.points[i]) * 3 + k];
    fillPhantomPoints(patch.boundaryMask, p);
}

void Evaluator::evalSource(const PointSource& src, float pos[3], float n[3]) const {
    float q[12][3], ds[3], dt[3];
    loadPoints(src.level, src.patch, q);
    const RegularPatch& patch = asset_.levels[src.level].regular[src.patch];
    evalCanonicalEdge(q, patch.points, patch.boundaryMask, src.edge, src.x, pos, ds, dt);
    cross(ds, dt, n);
}

// Rule 4: the normal of a sector's first patch at its corner.
void Evaluator::evalNormalSource(uint32_t normal, float n[3]) const {
    const NormalSource& ns = plan_->normals[normal];
    float q[12][3], pos[3], du[3], dv[3];
    loadPoints(ns.level, ns.patch, q);
    evalBoxSpline(q, kDomain[ns.corner][0], kDomain[ns.corner][1], pos, du, dv);
    cross(du, dv, n);
}

// Watertight rules of watertight.h for domain point (s,t) of regular patch `index`.
void Evaluator::evalWatertight(uint32_t level, uint32_t index, const float p[12][3], float s, float t,
                               const BoxWeights& w, float pos[3], float n[3], float dir[3], float du[3],
                               float dv[3]) const {
    const RegularPatch& patch = asset_.levels[level].regular[index];
    const WatertightLevel& wl = plan_->levels[level];
    float ds[3], dt[3];
    // du, dv: the patch's own derivatives, for the tangent (shared points take their
    // position and normal from a source, not their tangent).
    auto ownDerivatives = [&] {
        float own[3];
        if (tangents_) evalBoxSpline(p, w, own, du, dv);
    };
    int corner = s == 0.0f ? (t == 0.0f ? 0 : t == 1.0f ? 2 : -1) : (s == 1.0f && t == 0.0f ? 1 : -1);
    int edge = t == 0.0f ? 0 : s + t == 1.0f ? 1 : s == 0.0f ? 2 : -1;
    if (corner >= 0) {
        ownDerivatives();
        evalSource(plan_->points[wl.regularCorner[3 * index + corner]], pos, n);
        std::copy(n, n + 3, dir);  // rule 5
        uint32_t sector = wl.regularNormal[3 * index + corner];
        if (sector != kNoSource) evalNormalSource(sector, n);  // rule 4
        return;
    }
    if (edge < 0) {
        evalBoxSpline(p, w, pos, ds, dt);
        cross(ds, dt, n);
        std::copy(n, n + 3, dir);
        std::copy(ds, ds + 3, du);
        std::copy(dt, dt + 3, dv);
    } else {
        ownDerivatives();
        float local = edgeLocalParameter(edge, s, t);
        float x = edgeFlipped(patch.points, edge) ? 1.0f - local : local;
        uint32_t r = wl.regularEdge[3 * index + edge];
        if (r != kNoSource) {
            const EdgeRoot& root = plan_->roots[r];
            evalSource(PointSource{root.level, root.patch, root.edge, root.offset + root.scale * x}, pos, n);
        } else {
            evalCanonicalEdge(p, patch.points, patch.boundaryMask, edge, x, pos, ds, dt);
            cross(ds, dt, n);
        }
        std::copy(n, n + 3, dir);  // rule 5
        if (patch.boundaryMask & (1u << edge)) {  // rule 4: the position is shared, the normal this side's
            float own[3];
            evalBoxSpline(p, w, own, ds, dt);
            cross(ds, dt, n);
        }
    }
}

template <class F> void Evaluator::subDomains(uint32_t level, uint32_t index, bool split, F&& f) {
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

void Evaluator::countRegular(uint32_t level, uint32_t index, bool split, size_t& vertices, size_t& indices) {
    const bool indexed = settings_.indexed && drawsPatterns(settings_.path);
    vertices = indices = 0;
    subDomains(level, index, split, [&](const TessDomain& d, const int*) {
        vertices += indexed ? d.pointCount() : d.triangles.size();
        indices += indexed ? d.triangles.size() : 0;
    });
}

void Evaluator::regular(uint32_t level, uint32_t index, bool split) {
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
            const auto& [s, t, w] = dp[j];
            float pos[3], du[3], dv[3], n3[3], dir[3];
            if (plan_ && (s == 0.0f || t == 0.0f || s + t == 1.0f)) {
                evalWatertight(level, index, p, s, t, w, pos, n3, dir, du, dv);
            } else {
                for (int c = 0; c < 3; ++c) {
                    pos[c] = bp[size_t(c) * n + j];
                    du[c] = bu[size_t(c) * n + j];
                    dv[c] = bv[size_t(c) * n + j];
                }
                cross(du, dv, n3);
                std::copy(n3, n3 + 3, dir);
            }
            emit(pos, n3, dir, patch.param, s, t, du, dv);
        }
    });
}

PatchFactors Evaluator::factors(const RegularPatch& patch, uint32_t level, bool split) const {
    if (!splitIndex_)
        return levelPatchFactors(tessFactor_, level);
    PatchLodVertices lv;
    splitIndex_->find(patch, level, lv);  // incomplete tables: halves from the whole edge (lod.cpp)
    return screenPatchFactors(v_.data(), lv, level, split, settings_.lod.eye, lodScale(settings_.lod), tessFactor_);
}

// Position and tangents of limit stencil `st`; returns whether it is masked.
bool Evaluator::evalStencil(const LimitStencils& ls, uint32_t st, float pos[3], float tu[3], float tv[3]) {
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

void Evaluator::irregular(uint32_t levelIndex, uint32_t index) {
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
    if (irregularIndices())   // its own three corners
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
bool Evaluator::cornerDerivatives(const LimitStencils& ls, const IrregularFace& face, int c, const float tu[3],
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

const SmoothLimitWeights& Evaluator::smoothLimit(uint32_t valence) {
    auto it = cache_.smoothLimits.find(valence);
    if (it == cache_.smoothLimits.end()) it = cache_.smoothLimits.emplace(valence, loopSmoothLimitWeights(valence)).first;
    return it->second;
}

// Every output array sized for `vertices` and `indices`, keeping the allocations of
// an earlier frame.
void resize(const Asset& asset, size_t vertices, size_t indices, Tessellation& out) {
    out.positions.resize(3 * vertices);
    out.normals.resize(3 * vertices);
    out.face.resize(vertices);
    out.uv.resize(2 * vertices);
    const bool uvs = !asset.faceUVs.empty();
    out.texcoords.resize(uvs ? 2 * vertices : 0);
    out.tangents.resize(uvs ? 4 * vertices : 0);
    out.texcoords1.resize(asset.faceUV1s.empty() ? 0 : 2 * vertices);
    out.colors.resize(asset.faceColors.empty() ? 0 : 4 * vertices);
    out.indices.resize(indices);
}


} // namespace

uint32_t runtimeDepth(uint32_t maxDepth, float tessFactor) {
    uint32_t d = 0;
    while (d < maxDepth && std::ldexp(1.0f, int(d)) < tessFactor) ++d;
    return d;
}

struct CpuEvaluator::Impl {
    // One patch of the evaluation, in emission order, and where its output goes.
    struct Work {
        uint32_t level, index;
        bool irregular, split;
        size_t vertex, index0;   // its first vertex and first index in the output
    };
    const Asset& asset;
    std::unique_ptr<WatertightPlan> plan;  // built on the first watertight evaluation
    std::vector<float> vertices;           // the subdivided points: frames reuse the allocation
    std::vector<Work> work;                // this frame's patches
    std::vector<std::unique_ptr<EvalCache>> caches;   // one a thread (the counting pass uses the first)
};

CpuEvaluator::CpuEvaluator(const Asset& asset) : impl_(new Impl{asset, nullptr, {}, {}, {}}) {}
CpuEvaluator::~CpuEvaluator() = default;
CpuEvaluator::CpuEvaluator(CpuEvaluator&&) noexcept = default;
CpuEvaluator& CpuEvaluator::operator=(CpuEvaluator&&) noexcept = default;

void evaluateCpu(const Asset& asset, const float* controlPositions, const EvalSettings& settings, Tessellation& out) {
    CpuEvaluator(asset).evaluate(controlPositions, settings, out);
}


// Two passes: the patches' counts (on this thread), then their evaluation, in
// contiguous ranges of about equal vertex counts, one a thread, each writing its
// patches' vertices and indices in place. Each range's evaluator keeps caches of its
// own; what a patch emits depends only on the patch, so every thread count gives the
// same bits.
void CpuEvaluator::evaluate(const float* controlPositions, const EvalSettings& settings, Tessellation& out) {
    const Asset& asset = impl_->asset;
    float tessFactor = lodTessFactor(asset, controlPositions, settings);
    uint32_t depth = runtimeDepth(asset, tessFactor);
    std::vector<float>& vertices = impl_->vertices;
    subdivideCpu(asset, controlPositions, depth, vertices, settings.editValues);
    if (settings.watertight && !impl_->plan) {
        impl_->plan = std::make_unique<WatertightPlan>();
        buildWatertightPlan(asset, *impl_->plan);
    }
    const WatertightPlan* plan = settings.watertight ? impl_->plan.get() : nullptr;

    std::vector<Impl::Work>& work = impl_->work;
    work.clear();
    size_t vertexCount = 0, indexCount = 0;
    std::vector<std::unique_ptr<EvalCache>>& caches = impl_->caches;
    if (caches.empty()) caches.push_back(std::make_unique<EvalCache>());
    {
        Evaluator counter(asset, vertices, settings, tessFactor, plan, *caches[0], out);
        for (uint32_t l = 0; l <= depth; ++l) {
            const Level& level = asset.levels[l];
            for (uint32_t k = 0; k < level.regular.size(); ++k) {
                size_t v = 0, i = 0;
                counter.countRegular(l, k, l < depth, v, i);
                work.push_back({l, k, false, l < depth, vertexCount, indexCount});
                vertexCount += v, indexCount += i;
            }
            if (l == depth)
                for (uint32_t k = 0; k < level.irregular.size(); ++k) {
                    work.push_back({l, k, true, false, vertexCount, indexCount});
                    vertexCount += Evaluator::kIrregularVertices, indexCount += counter.irregularIndices();
                }
        }
    }
    resize(asset, vertexCount, indexCount, out);

    // Ranges of about kMinVertices or more: a thread costs more than it saves below.
    constexpr size_t kMinVertices = 16384;
    size_t threads = settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
    threads = std::max<size_t>(1, std::min({threads, work.size(), vertexCount / kMinVertices + 1}));
    auto range = [&](size_t t, size_t threadCount) {
        // The first patch whose first vertex is at or past t / n of the output.
        const size_t from = t * vertexCount / threadCount;
        return size_t(std::lower_bound(work.begin(), work.end(), from,
                                       [](const Impl::Work& w, size_t v) { return w.vertex < v; }) -
                      work.begin());
    };
    while (caches.size() < threads) caches.push_back(std::make_unique<EvalCache>());
    auto evaluateRange = [&](size_t t) {
        Evaluator eval(asset, vertices, settings, tessFactor, plan, *caches[t], out);
        for (size_t w = range(t, threads), end = range(t + 1, threads); w < end; ++w) {
            eval.at(work[w].vertex, work[w].index0);
            if (work[w].irregular) eval.irregular(work[w].level, work[w].index);
            else eval.regular(work[w].level, work[w].index, work[w].split);
        }
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(evaluateRange, t);
    evaluateRange(0);
    for (std::thread& th : pool) th.join();
}

} // namespace lt
