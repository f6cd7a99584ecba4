// cornerWeights (face_corner.h).
#include "face_corner.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

namespace lt {
namespace {

// A point as weights over the level-l points (the vertex and its neighbours: at
// most --max-valence + 1 columns), dense. PrimvarRefiner's primvar.
struct Weights {
    std::vector<double> w;
    void Clear() { std::fill(w.begin(), w.end(), 0.0); }
    void AddWithWeight(const Weights& src, double weight) {
        if (weight == 0) return;  // Sdc's masks pass zero weights too (a corner's edges)
        if (w.size() < src.w.size()) w.resize(src.w.size(), 0.0);
        for (size_t i = 0; i < src.w.size(); ++i) w[i] += weight * src.w[i];
    }
    void scale(double s) {
        for (double& x : w) x *= s;
    }
    double largest() const {
        double big = 0;
        for (double x : w) big = std::max(big, std::fabs(x));
        return big;
    }
    // this - o, over n columns.
    std::vector<double> minus(const Weights& o, size_t n) const {
        std::vector<double> d(n, 0.0);
        for (size_t i = 0; i < w.size(); ++i) d[i] += w[i];
        for (size_t i = 0; i < o.w.size(); ++i) d[i] -= o.w[i];
        return d;
    }
};

// The faces around one vertex as a mesh of its own.
struct Ring {
    std::vector<Weights> points;
    std::vector<int> faces;                      // 3 per face
    std::map<std::pair<int, int>, float> sharp;  // edge (smaller, larger) -> sharpness
    float vertexSharpness = 0;
    int vertex = 0;  // the corner's vertex
};

// The faces of `level` around `vertex`, in GetVertexFaces order; `pointOf` gives
// level's points as weights.
template <typename PointOf>
Ring ringOf(const Far::TopologyLevel& level, OsdIndex vertex, PointOf pointOf) {
    Ring r;
    std::map<OsdIndex, int> local;
    auto at = [&](OsdIndex v) {
        auto [it, added] = local.emplace(v, int(r.points.size()));
        if (added) r.points.push_back(pointOf(v));
        return it->second;
    };
    r.vertex = at(vertex);
    for (OsdIndex e : level.GetVertexEdges(vertex)) at(otherEnd(level, e, vertex));
    for (OsdIndex f : level.GetVertexFaces(vertex)) {
        auto fv = level.GetFaceVertices(f);
        auto fe = level.GetFaceEdges(f);
        for (int i = 0; i < 3; ++i) r.faces.push_back(at(fv[i]));
        for (int i = 0; i < 3; ++i)
            if (float s = level.GetEdgeSharpness(fe[i]); s > 0) {
                int a = at(fv[i]), b = at(fv[(i + 1) % 3]);
                r.sharp[{std::min(a, b), std::max(a, b)}] = s;
            }
    }
    r.vertexSharpness = level.GetVertexSharpness(vertex);
    return r;
}

std::unique_ptr<Far::TopologyRefiner> refinerOf(const Ring& r, const Sdc::Options& options) {
    FarTopology t;
    t.vertexCount = int(r.points.size());
    t.vertsPerFace.assign(r.faces.size() / 3, 3);
    t.faceVerts = r.faces;
    for (const auto& [e, s] : r.sharp) {
        t.creasePairs.insert(t.creasePairs.end(), {e.first, e.second});
        t.creaseWeights.push_back(s);
    }
    if (r.vertexSharpness > 0) {
        t.cornerVerts.push_back(r.vertex);
        t.cornerWeights.push_back(r.vertexSharpness);
    }
    std::unique_ptr<Far::TopologyRefiner> refiner = createRefiner(t.descriptor(), options);
    if (refiner) {
        Far::TopologyRefiner::UniformOptions uniform(1);
        uniform.fullTopologyInLastLevel = true;
        refiner->RefineUniform(uniform);
    }
    return refiner;
}

bool sameTopology(const Ring& a, const Ring& b) {
    return a.points.size() == b.points.size() && a.vertex == b.vertex && a.vertexSharpness == b.vertexSharpness &&
           a.faces == b.faces && a.sharp == b.sharp;
}

}  // namespace

bool cornerWeights(const Far::TopologyRefiner& refiner, int level, OsdIndex vertex, int steps, CornerWeights& out) {
    const Far::TopologyLevel& top = refiner.GetLevel(level);
    out.points.assign(1, vertex);
    for (OsdIndex e : top.GetVertexEdges(vertex)) out.points.push_back(otherEnd(top, e, vertex));
    auto faces = top.GetVertexFaces(vertex);
    out.faces.assign(faces.begin(), faces.end());
    const size_t n = out.points.size();
    std::map<OsdIndex, size_t> column;
    for (size_t i = 0; i < n; ++i) column.emplace(out.points[i], i);
    Ring r = ringOf(top, vertex, [&](OsdIndex v) {
        Weights p{std::vector<double>(n, 0.0)};
        p.w[column.at(v)] = 1.0;
        return p;
    });
    // Each face's descendant at the vertex, as an index into the ring's faces.
    std::vector<int> tracked(out.faces.size());
    for (size_t i = 0; i < tracked.size(); ++i) tracked[i] = int(i);
    // Once sharpness has decayed the ring's topology repeats level after level (a
    // vertex's child has the same faces and valence), so its refiner is reused.
    std::unique_ptr<Far::TopologyRefiner> local;
    Ring made;  // the ring `local` was made from
    for (int step = 0; step < steps; ++step) {
        if (!local || !sameTopology(r, made)) {
            local = refinerOf(r, refiner.GetSchemeOptions());
            if (!local) return false;
            made = r;
        }
        const Far::TopologyLevel& parent = local->GetLevel(0);
        const Far::TopologyLevel& child = local->GetLevel(1);
        std::vector<Weights> points(size_t(child.GetNumVertices()));
        Weights* src = r.points.data();
        Weights* dst = points.data();
        Far::PrimvarRefinerReal<double>(*local).Interpolate(1, src, dst);
        const OsdIndex v = parent.GetVertexChildVertex(r.vertex);
        auto childFaces = child.GetVertexFaces(v);
        for (int& t : tracked) {
            OsdIndex f = -1;
            for (OsdIndex c : parent.GetFaceChildFaces(t))
                if (localIndex(child, c, v) >= 0) f = c;
            auto at = std::find(childFaces.begin(), childFaces.end(), f);
            if (f < 0 || at == childFaces.end()) return false;
            t = int(at - childFaces.begin());
        }
        // Affine: keep the vertex where it is and the ring at unit size.
        const Weights centre = points[size_t(v)];
        double big = 0;
        for (Weights& p : points) {
            p.AddWithWeight(centre, -1.0);
            big = std::max(big, p.largest());
        }
        for (Weights& p : points) {
            p.scale(big > 0 ? 1.0 / big : 1.0);
            p.AddWithWeight(centre, 1.0);
        }
        r = ringOf(child, v, [&](OsdIndex x) { return points[size_t(x)]; });
    }
    out.corners.resize(tracked.size());
    for (size_t k = 0; k < tracked.size(); ++k) {
        const int* fv = &r.faces[size_t(tracked[k]) * 3];
        int at = 0;
        while (fv[at] != r.vertex) ++at;
        const Weights& o = r.points[size_t(r.vertex)];
        const Weights& a = r.points[size_t(fv[(at + 1) % 3])];
        const Weights& b = r.points[size_t(fv[(at + 2) % 3])];
        CornerWeights::Triangle& t = out.corners[k];
        t.edgeA = a.minus(o, n);
        t.edgeB = b.minus(o, n);
        t.edgeAB = b.minus(a, n);
        for (std::vector<double>* w : {&t.edgeA, &t.edgeB, &t.edgeAB}) rescaleWeights(*w);
    }
    return true;
}

const CornerWeights::Triangle* CornerWeights::of(OsdIndex face) const {
    auto at = std::find(faces.begin(), faces.end(), face);
    return at == faces.end() ? nullptr : &corners[size_t(at - faces.begin())];
}

}  // namespace lt
