// StencilOrienter (orient.h).
#include "orient.h"

#include "face_corner.h"
#include "looptess/tools/osd.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/sdc/crease.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace lt {
namespace {

// A level's points as PrimvarRefiner reads and writes them: 3 doubles a vertex in
// points_[l] itself (OsdPoint's arithmetic, without a copy).
struct PointRef {
    double* p;
    void Clear() { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const PointRef& src, double w) {
        for (int k = 0; k < 3; ++k) p[k] += w * src.p[k];
    }
};
struct Points {
    double* xyz;
    PointRef operator[](OsdIndex i) const { return {xyz + 3 * size_t(i)}; }
};

void cross(const double a[3], const double b[3], double n[3]) {
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
}

double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// What survives of tangent `t` = sum w_k (P[points_k] - P[points_0]) as a share of
// its terms' sizes, sum |w_k| |P[points_k] - P[points_0]| (0 when they are all 0).
double survives(const std::vector<double>& P, const std::vector<OsdIndex>& points, const std::vector<double>& w,
                const double t[3]) {
    const double* c = &P[size_t(points[0]) * 3];
    double terms = 0;
    for (size_t k = 1; k < points.size(); ++k) {
        const double* q = &P[size_t(points[k]) * 3];
        const double d[3] = {q[0] - c[0], q[1] - c[1], q[2] - c[2]};
        terms += std::abs(w[k]) * std::sqrt(dot(d, d));
    }
    return terms > 0 ? std::sqrt(dot(t, t)) / terms : 0.0;
}

// Whether tangent `t` cancels to 1e-5 of its terms' sizes (survives).
bool cancels(const std::vector<double>& P, const std::vector<OsdIndex>& points, const std::vector<double>& w,
             const double t[3]) {
    return survives(P, points, w, t) <= 1e-5;
}

// sum_k w_k (P[points_k] - P[points_0]).
void applyWeights(const std::vector<double>& P, const std::vector<OsdIndex>& points, const std::vector<double>& w,
                  double out[3]) {
    const double* c = &P[size_t(points[0]) * 3];
    out[0] = out[1] = out[2] = 0;
    for (size_t k = 1; k < points.size(); ++k)
        for (int i = 0; i < 3; ++i) out[i] += w[k] * (P[size_t(points[k]) * 3 + i] - c[i]);
}

}  // namespace

bool degenerateTangents(const std::vector<double>& P, const LimitStencil& s) {
    if (s.points.empty()) return false;
    const SmoothWeights* w = omittedWeights(s);
    const std::vector<double>& u = w ? w->tangentU : s.tangentU;
    const std::vector<double>& v = w ? w->tangentV : s.tangentV;
    double tu[3], tv[3], n[3];
    applyWeights(P, s.points, u, tu);
    applyWeights(P, s.points, v, tv);
    cross(tu, tv, n);
    // A tangent that cancels to 1e-5 of its terms' sizes is rounding noise on the
    // runtime's float points (coincident ring neighbours: ycb_mustard's valence-3
    // vertex 6706, whose two neighbours 6703 and 6707 coincide).
    return std::sqrt(dot(n, n)) <= 1e-6 * std::sqrt(dot(tu, tu) * dot(tv, tv)) ||  // a zero tangent too
           cancels(P, s.points, u, tu) || cancels(P, s.points, v, tv);
}

StencilOrienter::StencilOrienter(const Topology& topology, const std::vector<float>& positions) : topology_(topology) {
    const int levels = topology.maxLevel() + 1;
    points_.resize(size_t(levels));
    points_[0].assign(positions.begin(), positions.end());
    for (int l = 1; l < levels; ++l) {
        points_[size_t(l)].resize(3 * size_t(topology.level(l).GetNumVertices()));
        const Points src{points_[size_t(l) - 1].data()};
        Points dst{points_[size_t(l)].data()};
        Far::PrimvarRefinerReal<double>(topology.refiner(l - 1)).Interpolate(topology.local(l - 1) + 1, src, dst);
    }
    // Level K of the uniform refiner is level 0 of the adaptive one, numbered alike
    // (refine.cpp's levelDescriptor), so the links run across.
    parentVertex_.resize(size_t(levels));
    for (int l = 1; l < levels; ++l) {
        const Far::TopologyLevel& coarse = topology.level(l - 1);
        parentVertex_[size_t(l)].assign(size_t(topology.level(l).GetNumVertices()), -1);
        for (OsdIndex v = 0; v < coarse.GetNumVertices(); ++v)
            if (OsdIndex child = coarse.GetVertexChildVertex(v); child >= 0)
                parentVertex_[size_t(l)][size_t(child)] = v;
    }
}

void StencilOrienter::apply(int level, const std::vector<OsdIndex>& points, const std::vector<double>& w,
                            double out[3]) const {
    applyWeights(points_[size_t(level)], points, w, out);
}

const CornerWeights* StencilOrienter::corners(int level, OsdIndex vertex, int steps, Cache& cache) const {
    if (level != cache.level) {
        cache.corners.clear();
        cache.level = level;
    }
    auto [it, added] = cache.corners.emplace(std::make_pair(vertex, steps), CornerWeights{});
    if (added && !cornerWeights(topology_.refiner(level), topology_.local(level), vertex, steps, it->second)) {
        cache.corners.erase(it);
        return nullptr;
    }
    return &it->second;
}

StencilOrienter::Pair StencilOrienter::pair(int level, OsdIndex vertex, OsdIndex face, int steps, Cache& cache) const {
    const CornerWeights* c = corners(level, vertex, steps, cache);
    const CornerWeights::Triangle* t = c ? c->of(face) : nullptr;
    if (!t) return {};
    // The two edges at the triangle's largest angle (the smallest cosine): (A, B)
    // at v', (A, AB) at a, (B, AB) at b.
    double a[3], b[3], ab[3];
    apply(level, c->points, t->edgeA, a);
    apply(level, c->points, t->edgeB, b);
    apply(level, c->points, t->edgeAB, ab);
    auto cosine = [](const double x[3], const double y[3]) { return dot(x, y) / std::sqrt(dot(x, x) * dot(y, y)); };
    const double atV = cosine(a, b), atA = -cosine(a, ab), atB = cosine(b, ab);
    if (atV <= atA && atV <= atB) return {c, &t->edgeA, &t->edgeB};
    if (atA <= atB) return {c, &t->edgeA, &t->edgeAB};
    return {c, &t->edgeB, &t->edgeAB};
}

void StencilOrienter::orient(int level, LimitStencil& s, Cache& cache) const {
    if (s.smooth || s.points.empty()) return;
    const OsdIndex vertex = s.points[0];
    double tu[3], tv[3], n[3];
    apply(level, s.points, s.tangentU, tu);
    apply(level, s.points, s.tangentV, tv);
    cross(tu, tv, n);
    // The cosine between n and each sector face's corner normal, `steps` levels down.
    auto cosines = [&](int steps, std::vector<double>& out) {
        out.clear();
        const CornerWeights* c = corners(level, vertex, steps, cache);
        if (!c) return;
        for (OsdIndex face : c->faces) {
            if (limitSector(topology_.refiner(level), topology_.local(level), vertex, face) != s.sector) continue;
            const Pair p = pair(level, vertex, face, steps, cache);
            if (!p.corner) continue;
            double fn[3];
            pairCross(level, p, fn);
            const double len = std::sqrt(dot(n, n) * dot(fn, fn));
            if (len > 0) out.push_back(dot(n, fn) / len);
        }
    };
    // The sector's faces approach one normal; where some still point the other way
    // after kOrientSteps levels (a folded sector), deeper: on jaco_finger_distal
    // --crease-angle 40, vertex 155, one face's corner turns over between levels 1
    // and 2, four others' between 24 and 30, all facing the limit's way by 40.
    std::vector<double> c;
    for (int steps : {kOrientSteps, 24, 48, 96}) {
        cosines(steps, c);
        const bool agree = std::all_of(c.begin(), c.end(), [](double x) { return x > 0; }) ||
                           std::all_of(c.begin(), c.end(), [](double x) { return x < 0; });
        if (agree) break;
    }
    double vote = 0;
    for (double x : c) vote += x;
    if (vote < 0)
        for (double& w : s.tangentV) w = -w;
}

bool StencilOrienter::faceStencil(int level, OsdIndex vertex, OsdIndex face, int cornerLevel, int drawnLevel,
                                  const LimitStencil& shared, LimitStencil& out, Cache& cache) const {
    // Tangents that cancel in float at cornerLevel (a ring winding round the vertex
    // several times: the first harmonic, which decides the deep levels, is rounding
    // noise on its points) take the spike's level, the deepest drawn (spec "Faces
    // without a tangent plane").
    if (cornerLevel > drawnLevel && cancelsInFloat(level, vertex, face, cornerLevel, drawnLevel, cache))
        cornerLevel = drawnLevel;
    return ownCorner(level, vertex, face, cornerLevel, drawnLevel, shared, out, cache);
}

std::tuple<int, OsdIndex, OsdIndex> StencilOrienter::birth(int level, OsdIndex vertex, OsdIndex face) const {
    while (level > 0) {
        // A face at a vertex point is the child of a face at its parent vertex. A
        // vertex whose rule changed (semi-sharp edges decayed) has another stencil
        // from there on, judged anew.
        const OsdIndex parent = parentVertex_[size_t(level)][size_t(vertex)];
        if (parent < 0 ||
            topology_.level(level - 1).GetVertexRule(parent) != topology_.level(level).GetVertexRule(vertex))
            break;
        vertex = parent;
        face = topology_.parentFace(level, face);
        assert(face >= 0);
        --level;
    }
    return {level, vertex, face};
}

bool StencilOrienter::cancelsInFloat(int level, OsdIndex vertex, OsdIndex face, int cornerLevel, int drawnLevel,
                                     Cache& cache) const {
    const auto key = birth(level, vertex, face);
    if (auto it = cache.cancelled.find(key); it != cache.cancelled.end()) return it->second;
    const auto [b, v, f] = key;
    LimitStencil shared, own;
    limitStencil(topology_.refiner(b), topology_.local(b), v, f, shared);
    bool cancelled = false;
    if (ownCorner(b, v, f, cornerLevel, drawnLevel, shared, own, cache)) {
        const std::vector<double>& P = points_[size_t(b)];
        double tu[3], tv[3];
        applyWeights(P, own.points, own.tangentU, tu);
        applyWeights(P, own.points, own.tangentV, tv);
        cancelled = std::min(survives(P, own.points, own.tangentU, tu), survives(P, own.points, own.tangentV, tv)) <=
                    kFloatCancel;
    }
    return cache.cancelled[key] = cancelled;
}

bool StencilOrienter::ownCorner(int level, OsdIndex vertex, OsdIndex face, int cornerLevel, int drawnLevel,
                                const LimitStencil& shared, LimitStencil& out, Cache& cache) const {
    // The corner at cornerLevel, or where that triangle is too thin for float (a
    // ring of nearly collinear points: its angles reach 0 and 180 degrees), the
    // deepest level whose triangle is not, else the least thin (spec, "Faces
    // without a tangent plane").
    const int steps = std::max(cornerLevel - level, 0);
    Pair p = pair(level, vertex, face, steps, cache);
    if (!p.corner) return false;
    double thin = sine(level, p);
    for (int k = steps - 1; k >= 1 && thin <= kFloatSine; --k) {
        const Pair q = pair(level, vertex, face, k, cache);
        const double qThin = q.corner ? sine(level, q) : 0;
        if (qThin > thin) p = q, thin = qThin;
    }
    out.points = p.corner->points;
    out.tangentU = *p.u;
    out.tangentV = *p.v;
    // On the side the face is drawn on (spec "The side"): a corner may turn over as
    // it is refined (a flat sector folding past its crease, the fans of a pinch
    // flipping), and the level-K triangle's side is then not the one drawn.
    double n[3];
    pairCross(level, p, n);
    if (drawnAgainst(level, vertex, face, drawnLevel, n, cache))
        for (double& w : out.tangentV) w = -w;
    out.position.assign(out.points.size(), 0.0);
    for (size_t i = 0; i < shared.points.size(); ++i) {
        auto at = std::find(out.points.begin(), out.points.end(), shared.points[i]);
        out.position[size_t(at - out.points.begin())] += shared.position[i];
    }
    out.sector = -1;
    out.smooth = false;
    removeNullTangents(level, shared, out);
    // Only the neighbours it reads (a sheet of a non-manifold vertex reads its own).
    size_t kept = 1;
    for (size_t i = 1; i < out.points.size(); ++i) {
        if (out.position[i] == 0 && out.tangentU[i] == 0 && out.tangentV[i] == 0) continue;
        out.points[kept] = out.points[i];
        out.position[kept] = out.position[i];
        out.tangentU[kept] = out.tangentU[i];
        out.tangentV[kept] = out.tangentV[i];
        ++kept;
    }
    for (auto* w : {&out.position, &out.tangentU, &out.tangentV}) w->resize(kept);
    out.points.resize(kept);
    return true;
}

void StencilOrienter::removeNullTangents(int level, const LimitStencil& shared, LimitStencil& own) const {
    double extent = 0, t[3];
    const std::vector<double>& P = points_[size_t(level)];
    for (size_t k = 1; k < shared.points.size(); ++k)
        for (int i = 0; i < 3; ++i)
            extent =
                std::max(extent, std::fabs(P[size_t(shared.points[k]) * 3 + i] - P[size_t(shared.points[0]) * 3 + i]));
    for (const std::vector<double>* null : {&shared.tangentU, &shared.tangentV}) {
        apply(level, shared.points, *null, t);
        if (std::sqrt(dot(t, t)) > 1e-12 * extent) continue;
        // The null tangent over own's points.
        std::vector<double> z(own.points.size(), 0.0);
        for (size_t i = 0; i < shared.points.size(); ++i)
            z[size_t(std::find(own.points.begin(), own.points.end(), shared.points[i]) - own.points.begin())] +=
                (*null)[i];
        z[0] = 0;  // the vertex's weight is implied
        double zz = 0;
        for (double x : z) zz += x * x;
        if (zz == 0) continue;
        for (std::vector<double>* w : {&own.tangentU, &own.tangentV}) {
            double wz = 0;
            for (size_t i = 0; i < z.size(); ++i) wz += (*w)[i] * z[i];
            for (size_t i = 0; i < z.size(); ++i) (*w)[i] -= wz / zz * z[i];
            rescaleWeights(*w);
        }
    }
}

bool StencilOrienter::degenerate(int level, OsdIndex vertex, OsdIndex face, const LimitStencil& s, Cache& cache) const {
    const auto [b, v, f] = birth(level, vertex, face);
    if (b == level) return degenerateTangents(points_[size_t(level)], s);
    const Far::TopologyRefiner& refiner = topology_.refiner(b);
    const int local = topology_.local(b);
    const auto key = std::make_tuple(b, v, limitSector(refiner, local, v, f));
    if (auto it = cache.verdicts.find(key); it != cache.verdicts.end()) return it->second;
    LimitStencil first;
    limitStencil(refiner, local, v, f, first);
    return cache.verdicts[key] = degenerateTangents(points_[size_t(b)], first);
}

bool StencilOrienter::drawnAgainst(int level, OsdIndex vertex, OsdIndex face, int drawnLevel, const double n[3],
                                   Cache& cache) const {
    int birth = level;  // the level where the vertex first appears, and its face there
    for (; birth > 0 && parentVertex_[size_t(birth)][size_t(vertex)] >= 0; --birth) {
        vertex = parentVertex_[size_t(birth)][size_t(vertex)];
        face = topology_.parentFace(birth, face);
        assert(face >= 0);
    }
    // The corner triangle's normal at each drawn level with an area, once per corner
    // (every level's stencil of the corner asks).
    auto [it, added] = cache.drawn.emplace(std::make_tuple(birth, vertex, face), std::vector<std::array<double, 3>>{});
    if (added) {
        for (int steps = 0; birth + steps <= std::max(drawnLevel, birth); ++steps) {
            // At the stencil's own level through the level's cache (faceStencil asks it
            // for the same corners); a coarser birth level's without it, which would
            // drop the level's entries.
            CornerWeights fresh;
            const CornerWeights* c = &fresh;
            if (birth == level)
                c = corners(level, vertex, steps, cache);
            else if (!cornerWeights(topology_.refiner(birth), topology_.local(birth), vertex, steps, fresh))
                c = nullptr;
            const CornerWeights::Triangle* t = c ? c->of(face) : nullptr;
            if (!t) break;
            double a[3], b[3], m[3];
            apply(birth, c->points, t->edgeA, a);
            apply(birth, c->points, t->edgeB, b);
            cross(a, b, m);
            const double len = std::sqrt(dot(a, a) * dot(b, b));
            if (len > 0 && std::sqrt(dot(m, m)) > kAreaSine * len) it->second.push_back({m[0], m[1], m[2]});
        }
    }
    int along = 0, against = 0;
    for (const auto& m : it->second) (dot(m.data(), n) < 0 ? against : along) += 1;
    return against > along || (against == along && !it->second.empty() && dot(it->second[0].data(), n) < 0);
}

double StencilOrienter::pairCross(int level, const Pair& p, double n[3]) const {
    double a[3], b[3];
    apply(level, p.corner->points, *p.u, a);
    apply(level, p.corner->points, *p.v, b);
    cross(a, b, n);
    return std::sqrt(dot(a, a) * dot(b, b));
}

double StencilOrienter::sine(int level, const Pair& p) const {
    double n[3];
    const double len = pairCross(level, p, n);
    return len > 0 ? std::sqrt(dot(n, n)) / len : 0;
}

std::vector<SlitCorner> slitVertices(const Far::TopologyRefiner& unrefined, const std::vector<float>& positions) {
    const Far::TopologyLevel& level = unrefined.GetLevel(0);
    std::vector<SlitCorner> slits;
    if (positions.size() < size_t(level.GetNumVertices()) * 3) return slits;
    const std::vector<double> points(positions.begin(), positions.end());
    for (OsdIndex v = 0; v < level.GetNumVertices(); ++v) {
        // A crease position with no other sharpness, as patches.h's regular "crease"
        // corner; anything else is irregular already.
        if (level.IsVertexNonManifold(v) || level.GetVertexSharpness(v) > 0 ||
            level.GetVertexRule(v) != Sdc::Crease::RULE_CREASE || infSharpEdges(level, v) != 2)
            continue;
        bool semiSharp = false;
        for (OsdIndex e : level.GetVertexEdges(v)) semiSharp |= !isInfSharp(level, e) && level.GetEdgeSharpness(e) > 0;
        if (semiSharp) continue;
        std::vector<OsdIndex> sectors;
        for (OsdIndex f : level.GetVertexFaces(v)) {
            const OsdIndex sector = limitSector(unrefined, 0, v, f);
            if (std::find(sectors.begin(), sectors.end(), sector) != sectors.end()) continue;
            sectors.push_back(sector);
            LimitStencil s;
            limitStencil(unrefined, 0, v, f, s);
            // An open sector of k faces has k + 1 ring neighbours, r0 .. rk.
            if (s.points.size() != 1 + (3 + 1) || !degenerateTangents(points, s)) continue;
            for (OsdIndex g : level.GetVertexFaces(v)) {  // the middle face: (v, r1, r2)
                auto gv = level.GetFaceVertices(g);
                if (gv.FindIndex(s.points[2]) >= 0 && gv.FindIndex(s.points[3]) >= 0) slits.push_back({v, g});
            }
            break;
        }
    }
    return slits;
}

}  // namespace lt
