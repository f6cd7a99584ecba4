// The CPU evaluator's per-patch work (private to looptess_runtime): the domain
// points of a (sub-)triangle and their weights, the watertight rules, the vertices a
// patch emits. CpuEvaluator (cpu_evaluate.cpp) counts the patches, sizes the output
// and runs a PatchEvaluator per thread over a range of them.
//
// Tessellator convention (tess_domain.h): a sub-triangle (A, B, C) maps the
// tessellation coordinate (x, y, z) to (s,t) = z A + x B + y C, so outer[0] is
// edge C-A, outer[1] edge A-B, outer[2] edge B-C.
#pragma once

#include "looptess/runtime.h"

#include "box_spline.h"
#include "lod.h"
#include "subdivide_rules.h"
#include "tess_domain.h"
#include "watertight.h"

#include <array>
#include <cstring>
#include <map>
#include <memory>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace lt {

// A (sub-)triangle's domain points in the patch's (s,t), with their box-spline
// weights: the same for every patch drawn with that domain and sub-triangle, so
// made once, not per patch.
struct DomainPoint {
    float s, t;
};
struct DomainPoints {
    std::vector<DomainPoint> points;
    std::vector<float> weights;  // by kind (w, ds, dt), point 0..11, then domain point (evalBoxSplineBatch)
    size_t size() const { return points.size(); }
    const DomainPoint& operator[](size_t i) const { return points[i]; }
};

// What evaluators build once and keep across frames (a CpuEvaluator holds one per
// thread): domains, their points' weights, smooth limit weights. The domains are
// those of one mode (refinement patterns, or the tessellator's spacing); a frame of
// another mode starts them afresh.
struct EvalCache {
    int mode = -1;
    std::map<std::array<float, 4>, TessDomain> domains;  // std::map: the addresses stay
    std::map<std::tuple<const TessDomain*, int, int, int>, DomainPoints> domainPoints;
    size_t domainCount = 0, domainPointCount = 0;  // points in each map
    std::map<uint32_t, SmoothLimitWeights> smoothLimits;
    // boxSplineWeights(s, t) by the bits of (s, t), for the watertight rules' points
    // on patch edges and corners, which the domains' own weights do not hold.
    std::unordered_map<uint64_t, BoxWeights> weights;
    // Rule 3's shared corner points of this frame by watertight source: position and
    // normal (6 floats), valid where cornerFrame equals frame. A corner is met by every
    // patch around its vertex; the sources depend on the frame's control points.
    std::vector<float> corners;
    std::vector<uint32_t> cornerFrame;
    uint32_t frame = 0;
    // Bounded (about 10 MB each): at screen-space factors most patches have domains
    // of their own, and a moving camera makes new ones every frame.
    static constexpr size_t kMaxPoints = size_t(1) << 16;

    const BoxWeights& weightsAt(float s, float t) {
        uint32_t a, b;
        std::memcpy(&a, &s, 4);
        std::memcpy(&b, &t, 4);
        if (weights.size() > kMaxPoints) weights.clear();
        auto [it, added] = weights.try_emplace(uint64_t(a) << 32 | b);
        if (added) it->second = boxSplineWeights(s, t);
        return it->second;
    }
};

class PatchEvaluator {
public:
    // `tessFactor`: F of `settings` (lodTessFactor).
    // `plan`: watertight sources (null: each patch evaluates alone).
    // `splitIndex`: the asset's, in Screen mode (else null).
    // `cache`: this evaluator's, kept by its owner across frames.
    PatchEvaluator(const Asset& asset, const std::vector<float>& vertices, const EvalSettings& settings,
                   float tessFactor, const WatertightPlan* plan, const SplitVertexIndex* splitIndex, EvalCache& cache,
                   Tessellation& out)
        : asset_(asset),
          v_(vertices),
          settings_(settings),
          tessFactor_(tessFactor),
          plan_(plan),
          splitIndex_(splitIndex),
          cache_(cache),
          out_(out) {
        displace_ = settings.displace && asset.displacement.present();
        tangents_ = settings.attributes && !asset.faceUVs.empty();
        texcoords1_ = settings.attributes && !asset.faceUV1s.empty();
        colors_ = settings.attributes && !asset.faceColors.empty();
        const int mode = drawsPatterns(settings.path) ? 2 : int(settings.spacing == Spacing::FractionalOdd);
        if (cache.mode != mode) {
            cache.domainPoints.clear();
            cache.domains.clear();
            cache.domainCount = cache.domainPointCount = 0;
            cache.mode = mode;
        }
        if (plan) {  // a new frame: no corner point evaluated yet
            if (++cache.frame == 0) {
                cache.cornerFrame.assign(cache.cornerFrame.size(), 0);
                cache.frame = 1;
            }
            cache.corners.resize(6 * plan->points.size());
            cache.cornerFrame.resize(plan->points.size(), 0);
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
    const DomainPoints& domainPoints(const TessDomain& d, const int corners[3]);  // valid until the next call
    // Calls f(domain, corners) for each (sub-)triangle regular patch `index` is drawn
    // as, in order, after `prepare(factors)`.
    template <class F>
    void subDomains(uint32_t level, uint32_t index, bool split, F&& f);
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
    // ownDu, ownDv: the patch's own derivatives at (s,t) (its box-spline sums).
    void evalWatertight(uint32_t level, uint32_t index, const float p[12][3], float s, float t, const float ownDu[3],
                        const float ownDv[3], float pos[3], float n[3], float dir[3], float du[3], float dv[3]) const;

    // countRegular's results outside Screen mode, where a patch's counts depend only on
    // its level, whether it is split and its split mask (subDomains): by level, then
    // the mask when split (a valid asset's is below 8), 8 when not.
    struct Counts {
        size_t vertices = 0, indices = 0;
        bool known = false;
    };
    std::vector<std::array<Counts, 9>> counts_;

    const Asset& asset_;
    const std::vector<float>& v_;
    EvalSettings settings_;
    float tessFactor_;
    const WatertightPlan* plan_;
    const SplitVertexIndex* splitIndex_;  // Screen mode only
    EvalCache& cache_;
    bool displace_ = false;
    bool tangents_ = false;  // TEXCOORD_0 and TANGENT: the asset has TEXCOORD_0 and settings.attributes
    bool texcoords1_ = false, colors_ = false;  // TEXCOORD_1, COLOR_0 likewise
    Tessellation& out_;
    size_t vertex_ = 0, index_ = 0;  // where the next vertex and index go in out_
    std::vector<float> batch_;       // regular(): one domain's positions and derivatives
};

}  // namespace lt
