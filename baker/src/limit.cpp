// Exact limit stencils for the corners of irregular patches.
//
// Sdc's limit masks are exact only for stationary configurations: a smooth vertex
// (no sharpness at all), a crease or corner position. They are not exact for a
// vertex whose semi-sharp edges have not decayed yet, for darts, or for the
// across-crease tangent at an extraordinary crease or boundary valence. So the
// baker refines the vertex's own 1-ring locally -- the 1-ring of a vertex's child
// is a combination of the vertex's 1-ring, with the sharpness rules of Sdc -- until
// every sharpness is 0 or infinite, then further while the rule is not smooth, so
// the configuration converges to its characteristic one; then applies Sdc's masks.
//
// Sectors. Infinitely sharp edges (boundaries included) cut the faces around a
// vertex into sectors with their own tangent planes. The stencil of a corner of a
// face is computed on the sector that holds the face, as a boundary vertex:
//
//        r2    r1                 sector of face f, counter-clockwise from its
//          \  f1 |                leading sharp edge (v, r0) to its trailing one
//       f2  \    |  f0            (v, r3): rings r0..r3, faces f0..f2 between them
//     r3 ==== v ==== r0   <- sharp edges
//
// To avoid cancellation the local state is the vertex v and the differences
// d_j = r_j - v, each as weights over the original points (v, r_0, ..., r_m-1):
// masks are affine, so v' - v and r'_j - v' are combinations of the d_j alone.
#include "refine.h"

#include <opensubdiv/sdc/crease.h>
#include <opensubdiv/sdc/loopScheme.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>

namespace lt {
namespace {

using Rule = Sdc::Crease::Rule;
using LoopScheme = Sdc::Scheme<Sdc::SCHEME_LOOP>;

// A vertex with a ring of m edges; open (a sector, faces between consecutive
// edges only) or closed (a face also between edge m-1 and edge 0).
// A sector's vertex still has the rule of its whole ring: semi-sharp edges in other
// sectors keep it a corner until they decay (two infinitely sharp edges and a
// semi-sharp one: a corner, then a crease). So the hood carries their sharpness too.
struct Hood {
    bool closed = true;
    float vertexSharpness = 0;
    int m = 0;                     // the sector's ring edges
    std::vector<float> sharpness;  // every edge of the vertex, the sector's m first (no others when closed)
    int edges() const { return m; }
    int faces() const { return closed ? edges() : edges() - 1; }
};

// Sdc's view of the hood's vertex: the sector's edges, then (`whole`) the others,
// which decide the rule (and a fractional rule's weight) but never take a weight:
// a sector is bounded by the two infinitely sharp edges that any crease rule uses.
class HoodVertex {
public:
    HoodVertex(const Hood& h, bool whole) : h_(h), edges_(whole ? int(h.sharpness.size()) : h.m) {}
    int GetNumEdges() const { return edges_; }
    int GetNumFaces() const { return h_.closed ? GetNumEdges() : GetNumEdges() - 1; }
    float GetSharpness() const { return h_.vertexSharpness; }
    float* GetSharpnessPerEdge(float s[]) const {
        std::copy_n(h_.sharpness.begin(), edges_, s);
        return s;
    }
    float GetChildSharpness(const Sdc::Crease& c) const { return c.SubdivideVertexSharpness(h_.vertexSharpness); }
    float* GetChildSharpnessPerEdge(const Sdc::Crease& c, float s[]) const {
        c.SubdivideEdgeSharpnessesAroundVertex(GetNumEdges(), h_.sharpness.data(), s);
        return s;
    }

private:
    const Hood& h_;
    int edges_;
};

class HoodEdge {
public:
    HoodEdge(int faces, float sharpness) : faces_(faces), sharpness_(sharpness) {}
    int GetNumFaces() const { return faces_; }
    float GetSharpness() const { return sharpness_; }
    void GetChildSharpnesses(const Sdc::Crease&, float s[2]) const { s[0] = s[1] = sharpness_ - 1.0f; }
    void GetNumVerticesPerFace(int counts[]) const { counts[0] = counts[1] = 3; }

private:
    int faces_;
    float sharpness_;
};

Rule vertexRule(const Sdc::Crease& crease, const Hood& h) {
    return crease.DetermineVertexVertexRule(h.vertexSharpness, int(h.sharpness.size()), h.sharpness.data());
}

bool stationary(const Hood& h) {
    auto fixed = [](float s) { return Sdc::Crease::IsSmooth(s) || Sdc::Crease::IsInfinite(s); };
    return fixed(h.vertexSharpness) && std::all_of(h.sharpness.begin(), h.sharpness.end(), fixed);
}

// y += a x over n weights (over the original points v, r_0, ...).
void axpy(double* y, double a, const double* x, size_t n) {
    for (size_t i = 0; i < n; ++i) y[i] += a * x[i];
}

// The local configuration: v and d_j, with the sharpness that governs them, and
// the buffers a refinement step reuses (limitStencil runs per corner: no
// allocation per step or per call once they have grown).
struct Local {
    Hood hood;
    size_t n = 0;           // weights per point: the vertex and its m neighbours
    std::vector<double> v;  // v as weights
    std::vector<double> d;  // d_j = r_j - v as weights, m rows of n
    double* row(int j) { return d.data() + size_t(j) * n; }
    // refine's scratch.
    Hood child;
    std::vector<double> dv, nd, ew, fw;
    std::vector<OsdIndex> edges;  // limitStencil's ring
};

// The largest valence whose weight matrices limitStencil's buffers keep between calls.
constexpr int kKeptValence = 64;

// The configuration before any step: v = the vertex, d_j = r_j - v, for s.hood.m
// ring points.
void start(Local& s) {
    const int m = s.hood.m;
    const size_t n = size_t(m) + 1;
    s.n = n;
    s.v.assign(n, 0.0);
    s.v[0] = 1.0;
    s.d.assign(size_t(m) * n, 0.0);
    for (int k = 0; k < m; ++k) {
        s.row(k)[0] = -1.0;
        s.row(k)[size_t(k) + 1] = 1.0;
    }
}

// One step of Loop subdivision of the local configuration.
void refine(const Sdc::Options& options, Local& s) {
    const int m = s.hood.edges();
    const size_t n = s.n, all = s.hood.sharpness.size();
    Sdc::Crease crease(options);
    LoopScheme scheme(options);

    Hood& child = s.child;
    child.closed = s.hood.closed;
    child.m = m;
    child.vertexSharpness = crease.SubdivideVertexSharpness(s.hood.vertexSharpness);
    child.sharpness.resize(all);
    crease.SubdivideEdgeSharpnessesAroundVertex(int(all), s.hood.sharpness.data(), child.sharpness.data());

    // Vertex point: v' - v = sum_k b_k d_k.
    double vw = 0;
    s.ew.assign(all + 1, 0.0);
    s.fw.assign(all + 1, 0.0);
    SdcMask vmask(&vw, s.ew.data(), s.fw.data());
    scheme.ComputeVertexVertexMask(HoodVertex(s.hood, true), vmask, vertexRule(crease, s.hood),
                                   vertexRule(crease, child));
    s.dv.assign(n, 0.0);
    if (vmask.GetNumEdgeWeights() > 0) {
        for (int k = 0; k < m; ++k) axpy(s.dv.data(), s.ew[k], s.row(k), n);
        for (size_t k = size_t(m); k < all; ++k) assert(s.ew[k] == 0.0 && "edges outside the sector take no weight");
    }

    // Edge points: e_i - v = a_r d_i + f (d_(i-1) + d_(i+1)), then minus (v' - v).
    s.nd.assign(size_t(m) * n, 0.0);
    for (int i = 0; i < m; ++i) {
        bool single = !s.hood.closed && (i == 0 || i == m - 1);
        float sharp = s.hood.sharpness[size_t(i)];
        double ev[2] = {0, 0}, ef[2] = {0, 0};
        SdcMask emask(ev, ev, ef);
        Rule pRule = sharp > 0 ? Rule::RULE_CREASE : Rule::RULE_SMOOTH;
        Rule cRule = crease.SubdivideUniformSharpness(sharp) > 0 ? Rule::RULE_CREASE : Rule::RULE_SMOOTH;
        scheme.ComputeEdgeVertexMask(HoodEdge(single ? 1 : 2, sharp), emask, pRule, cRule);
        double* out = s.nd.data() + size_t(i) * n;
        axpy(out, ev[1], s.row(i), n);
        if (emask.GetNumFaceWeights() > 0) {
            int prev = (i + m - 1) % m, next = (i + 1) % m;
            if (s.hood.closed || i > 0) axpy(out, ef[0], s.row(prev), n);
            if (s.hood.closed || i < m - 1) axpy(out, ef[single ? 0 : 1], s.row(next), n);
        }
        axpy(out, -1.0, s.dv.data(), n);
    }
    axpy(s.v.data(), 1.0, s.dv.data(), n);
    s.d.swap(s.nd);
    std::swap(s.hood, s.child);
}

// Limit masks of the final configuration, as weights over the original points.
void applyLimitMasks(const Sdc::Options& options, Local& s, LimitStencil& out) {
    const int m = s.hood.edges();
    const size_t n = s.n, columns = size_t(m) + 1;
    Sdc::Crease crease(options);
    // Edge weights then face weights of the three masks, in the scratch buffers.
    s.ew.assign(3 * columns, 0.0);
    s.fw.assign(3 * columns, 0.0);
    double vw[3] = {0, 0, 0}, *w[3], *fw[3];
    for (int i = 0; i < 3; ++i) {
        w[i] = s.ew.data() + size_t(i) * columns;
        fw[i] = s.fw.data() + size_t(i) * columns;
    }
    SdcMask pos(&vw[0], w[0], fw[0]), tu(&vw[1], w[1], fw[1]), tv(&vw[2], w[2], fw[2]);
    // Stationary: the edges outside the sector no longer change the rule.
    LoopScheme(options).ComputeVertexLimitMask(HoodVertex(s.hood, false), pos, tu, tv, vertexRule(crease, s.hood));
    out.position = s.v;
    out.tangentU.assign(n, 0.0);
    out.tangentV.assign(n, 0.0);
    for (int k = 0; k < m; ++k) {
        if (pos.GetNumEdgeWeights() > 0) axpy(out.position.data(), w[0][k], s.row(k), n);
        if (tu.GetNumEdgeWeights() > 0) axpy(out.tangentU.data(), w[1][k], s.row(k), n);
        if (tv.GetNumEdgeWeights() > 0) axpy(out.tangentV.data(), w[2][k], s.row(k), n);
    }
    // Tangents shrink with every local step; only their direction matters.
    rescaleWeights(out.tangentU);
    rescaleWeights(out.tangentV);
}

// The ring of `vertex` around `face`, counter-clockwise: the whole ring when no
// infinitely sharp edge cuts it (closed), else the sector holding `face`.
// `first`: the sector's first face, whose leading edge is edges[0]. Returns false
// for configurations the walk cannot follow (non-manifold).
bool gatherRing(const Far::TopologyLevel& level, OsdIndex vertex, OsdIndex face, std::vector<OsdIndex>& edges,
                bool& closed, OsdIndex* firstFace = nullptr) {
    // One infinitely sharp edge (a dart) does not cut the ring: darts have a
    // tangent plane. Two or more do.
    const int sharpEdges = infSharpEdges(level, vertex);
    bool cuts = sharpEdges >= 2;
    // Walk clockwise (across leading edges) to the sector's first face.
    OsdIndex f = face;
    int limit = level.GetVertexFaces(vertex).size() + 1;
    closed = false;
    for (int step = 0;; ++step) {
        if (step > limit) return false;
        OsdIndex lead = level.GetFaceEdges(f)[localIndex(level, f, vertex)];
        if (cuts && isInfSharp(level, lead)) break;
        OsdIndex g = otherFace(level, lead, f);
        if (g < 0) return false;
        if (g == face) {
            closed = true;
            break;
        }
        f = g;
    }
    // Then counter-clockwise: the leading edge of the first face, then trailing edges.
    OsdIndex first = f;
    if (firstFace) *firstFace = f;
    edges.assign(1, level.GetFaceEdges(f)[localIndex(level, f, vertex)]);
    for (int step = 0;; ++step) {
        if (step > limit) return false;
        OsdIndex trail = level.GetFaceEdges(f)[(localIndex(level, f, vertex) + 2) % 3];
        if (!closed && cuts && isInfSharp(level, trail)) {
            edges.push_back(trail);
            break;
        }
        OsdIndex g = otherFace(level, trail, f);
        if (closed && g == first) break;
        if (g < 0) return false;
        edges.push_back(trail);
        f = g;
    }
    return true;
}

// A sheet (refine.h, tangentPlaneAt): a non-manifold vertex inside an edge of
// three or more faces -- not infinitely sharp, on exactly two infinitely sharp
// edges, as OpenSubdiv makes such an edge's points. OpenSubdiv's crease rule reads
// only the two edges' ends, and the smooth edges' rule only the faces beside each
// edge, so each sheet's faces between the two edges refine as a crease sector of a
// manifold vertex would: `edges` is that sector's ring, `key` its first face (the
// sheets share their leading edges, so LimitStencil::sector names them by face).
// False where `vertex` is no sheet, or `face`'s faces start and end on one of the
// two edges (its crease rule then reads the other edge, outside them).
bool sheetRing(const Far::TopologyLevel& level, OsdIndex vertex, OsdIndex face, std::vector<OsdIndex>& edges,
               bool& closed, OsdIndex& key) {
    if (!level.IsVertexNonManifold(vertex) || level.IsVertexInfSharp(vertex) || infSharpEdges(level, vertex) != 2)
        return false;
    return gatherRing(level, vertex, face, edges, closed, &key) && !closed && edges.front() != edges.back();
}

}  // namespace

OsdIndex limitSector(const Far::TopologyRefiner& refiner, int levelIndex, OsdIndex vertex, OsdIndex face) {
    const Far::TopologyLevel& level = refiner.GetLevel(levelIndex);
    std::vector<OsdIndex> edges;
    bool closed = true;
    OsdIndex sheet = -1;
    if (level.IsVertexNonManifold(vertex)) return sheetRing(level, vertex, face, edges, closed, sheet) ? sheet : -1;
    const int sharpEdges = infSharpEdges(level, vertex);
    if (sharpEdges < 2) return -1;  // one tangent plane: no need to walk the ring
    if (!gatherRing(level, vertex, face, edges, closed)) return -1;
    return closed ? -1 : edges[0];
}

void rescaleWeights(std::vector<double>& w) {
    double big = 0;
    for (double x : w) big = std::max(big, std::fabs(x));
    if (big > 0)
        for (double& x : w) x /= big;
}

bool tangentPlaneAt(const Far::TopologyRefiner& refiner, int levelIndex, OsdIndex vertex, OsdIndex face) {
    const Far::TopologyLevel& level = refiner.GetLevel(levelIndex);
    std::vector<OsdIndex> edges;
    bool closed = true;
    // A sheet's sector is a crease sector (below); other non-manifold vertices are spikes.
    OsdIndex sheet;
    if (level.IsVertexNonManifold(vertex))
        return sheetRing(level, vertex, face, edges, closed, sheet) && edges.size() < 7;
    const int sharpEdges = infSharpEdges(level, vertex);
    const bool infSharp = level.IsVertexInfSharp(vertex);
    if (infSharp && sharpEdges < 2) return false;  // a cone
    if (sharpEdges < 2) return true;
    if (!gatherRing(level, vertex, face, edges, closed) || closed) return true;
    const size_t faces = edges.size() - 1;
    // A lasting sharp corner: a plane only when its sector is one face.
    if (sharpEdges >= 3 || infSharp) return faces == 1;
    // A crease or boundary sector of k faces: Loop's smooth edge rule beside the
    // crease rule gives its interior modes 3/8 + cos(pi m / k) / 4, the first
    // above the crease tangent's 1/2 from k = 4 and the second equal to it at
    // k = 6, above it from k = 7: from six faces on, faces at the sector's ends
    // and in its middle approach different normals.
    return faces < 6;
}

void limitStencil(const Far::TopologyRefiner& refiner, int levelIndex, OsdIndex vertex, OsdIndex face,
                  LimitStencil& out, bool smoothWeights) {
    const Far::TopologyLevel& level = refiner.GetLevel(levelIndex);
    const Sdc::Options options = refiner.GetSchemeOptions();
    thread_local Local s;  // its buffers, reused by every call on this thread
    std::vector<OsdIndex>& edges = s.edges;
    const int sharpEdges = infSharpEdges(level, vertex);
    // Refined locally where the ring is a manifold vertex's, or a sector of one.
    bool refinable = true;
    OsdIndex sheet = -1;
    if (level.IsVertexNonManifold(vertex)) {
        refinable = sheetRing(level, vertex, face, edges, s.hood.closed, sheet);
    } else if (sharpEdges < 2 && !level.IsVertexBoundary(vertex)) {
        // One tangent plane: the whole ring, in OpenSubdiv's counter-clockwise order.
        auto all = level.GetVertexEdges(vertex);
        edges.assign(all.begin(), all.end());
        s.hood.closed = true;
    } else {
        refinable = gatherRing(level, vertex, face, edges, s.hood.closed);
    }
    if (!refinable) {
        // OpenSubdiv's own ring and rule: non-manifold vertices other than sheets are
        // sharp, so the masks are those of a stationary crease or corner.
        auto all = level.GetVertexEdges(vertex);
        edges.assign(all.begin(), all.end());
        s.hood.closed = !level.IsVertexBoundary(vertex);
    }
    const int m = int(edges.size());
    s.hood.m = m;
    s.hood.vertexSharpness = level.GetVertexSharpness(vertex);
    // A sector shows only its two bounding sharp edges: keep the rule of a vertex
    // with more of them (a corner) by making the sector's vertex infinitely sharp.
    if (!s.hood.closed && sharpEdges > 2) s.hood.vertexSharpness = Sdc::Crease::SHARPNESS_INFINITE;
    s.hood.sharpness.resize(size_t(m));
    out.points.clear();
    out.points.reserve(size_t(m) + 1);
    out.points.push_back(vertex);
    for (int k = 0; k < m; ++k) {
        s.hood.sharpness[size_t(k)] = level.GetEdgeSharpness(edges[size_t(k)]);
        out.points.push_back(otherEnd(level, edges[size_t(k)], vertex));
    }
    if (!s.hood.closed)
        for (OsdIndex e : level.GetVertexEdges(vertex))
            if (std::find(edges.begin(), edges.end(), e) == edges.end())
                s.hood.sharpness.push_back(level.GetEdgeSharpness(e));
    out.sector = sheet >= 0 ? sheet : s.hood.closed ? -1 : edges[0];
    // Smooth (no sharpness on a closed manifold ring: Loop's smooth rule, no local
    // step): the weights depend on the valence alone.
    const bool smooth = s.hood.closed && refinable && s.hood.vertexSharpness == 0 &&
                        std::all_of(s.hood.sharpness.begin(), s.hood.sharpness.end(), [](float x) { return x == 0; });
    out.smooth = smooth;
    if (smooth) {
        if (smoothWeights) {
            const SmoothWeights& w = smoothLimitWeights(m);
            out.position = w.position;
            out.tangentU = w.tangentU;
            out.tangentV = w.tangentV;
        } else {
            out.position.clear();
            out.tangentU.clear();
            out.tangentV.clear();
        }
        return;
    }
    start(s);

    // Refine until the sharpness is stationary, then on while the rule is not the
    // smooth one (whose masks are exact) so non-smooth configurations converge.
    Sdc::Crease crease(options);
    const int kSettle = 48;
    int extra = 0;
    for (int step = 0; step < 64 && refinable; ++step) {
        bool fixed = stationary(s.hood);
        Rule rule = vertexRule(crease, s.hood);
        bool smoothNoSharp = rule == Rule::RULE_SMOOTH;
        if (fixed && (smoothNoSharp || extra++ >= kSettle)) break;
        refine(options, s);
    }
    applyLimitMasks(options, s, out);
    // A rare high valence's (m^2 doubles) matrices are not kept for the thread's life.
    if (m > kKeptValence) {
        std::vector<double>().swap(s.d);
        std::vector<double>().swap(s.nd);
    }
}

const SmoothWeights& smoothLimitWeights(int valence) {
    assert(valence >= 0);
    thread_local std::vector<std::unique_ptr<SmoothWeights>> byValence;  // null until computed
    if (byValence.size() <= size_t(valence)) byValence.resize(size_t(valence) + 1);
    std::unique_ptr<SmoothWeights>& w = byValence[size_t(valence)];
    if (!w) {
        // limitStencil's path on a closed ring without sharpness: no local step.
        Local s;
        s.hood.m = valence;
        s.hood.sharpness.assign(size_t(valence), 0.0f);
        start(s);
        LimitStencil out;
        applyLimitMasks(Sdc::Options(), s, out);
        w.reset(new SmoothWeights{std::move(out.position), std::move(out.tangentU), std::move(out.tangentV)});
    }
    return *w;
}

const SmoothWeights* omittedWeights(const LimitStencil& s) {
    if (!s.smooth || !s.position.empty() || s.points.empty()) return nullptr;
    return &smoothLimitWeights(int(s.points.size()) - 1);
}

const LimitStencil& withWeights(const LimitStencil& s, LimitStencil& scratch) {
    const SmoothWeights* w = omittedWeights(s);
    if (!w) return s;
    scratch.points = s.points;
    scratch.position = w->position;
    scratch.tangentU = w->tangentU;
    scratch.tangentV = w->tangentV;
    scratch.sector = s.sector;
    scratch.smooth = true;
    return scratch;
}

}  // namespace lt
