// OpenSubdiv oracle (looptess/tools/osd_reference.h).
#include "looptess/tools/osd_reference.h"

#include "osd_edits.h"     // the uniform prefix of an edited mesh
#include "osd_topology.h"  // the oracle's own Far topology of a mesh

#include "looptess/tools/osd.h"  // SdcMask: storage for Sdc's masks, nothing of the mapping

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/sdc/loopScheme.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace lt {
namespace {

using Point = OsdPoint;

// `control` (the refiner's level-0 points) followed by every refined vertex of
// every level.
std::vector<Point> refinedPoints(const Far::TopologyRefiner& refiner, std::vector<Point> control) {
    std::vector<Point> all = std::move(control);
    all.resize(size_t(refiner.GetNumVerticesTotal()));
    Far::PrimvarRefinerReal<double> primvar(refiner);
    Point* src = all.data();
    for (int l = 1; l <= refiner.GetMaxLevel(); ++l) {
        Point* dst = src + refiner.GetLevel(l - 1).GetNumVertices();
        primvar.Interpolate(l, src, dst);
        src = dst;
    }
    return all;
}

bool isSharp(const Far::TopologyLevel& base, OsdIndex edge) {
    return base.IsEdgeInfSharp(edge) || base.IsEdgeBoundary(edge);
}

// The infinitely sharp or boundary edges at `vertex`.
int sharpEdgeCount(const Far::TopologyLevel& base, OsdIndex vertex) {
    int n = 0;
    for (OsdIndex e : base.GetVertexEdges(vertex)) n += isSharp(base, e);
    return n;
}

// At a vertex with two or more infinitely sharp or boundary edges, the number of
// faces in the sector of `face` at its corner `vertex` (between the sharp edges
// around it); 0 elsewhere.
int sectorFaces(const Far::TopologyLevel& base, int face, OsdIndex vertex) {
    if (base.IsVertexNonManifold(vertex)) return 0;
    auto sharp = [&](OsdIndex e) { return isSharp(base, e); };
    if (sharpEdgeCount(base, vertex) < 2) return 0;
    // Each way round the vertex from `face` (`step` 1: over each face's edge to its
    // next corner; 2: to its previous one), across edges that are not sharp.
    int faces = 1;
    for (int step : {1, 2}) {
        OsdIndex f = face;
        for (int guard = 0; guard <= base.GetVertexFaces(vertex).size(); ++guard) {
            const auto vs = base.GetFaceVertices(f);
            int at = 0;
            while (at < 3 && vs[at] != vertex) ++at;
            const OsdIndex e = at < 3 ? base.FindEdge(vertex, vs[(at + step) % 3]) : -1;
            if (e < 0 || sharp(e) || base.GetEdgeFaces(e).size() != 2) break;
            const auto ef = base.GetEdgeFaces(e);
            f = ef[0] == f ? ef[1] : ef[0];
            if (f == face) break;
            ++faces;
        }
    }
    return faces;
}

// The crease and boundary vertices of `base` with a run of three faces between their
// two infinitely sharp or boundary edges and no other sharpness: where a regular
// patch could take the run, and where the baker isolates the slit tips among them.
std::vector<int> threeFaceRuns(const Far::TopologyLevel& base) {
    std::vector<int> runs;
    for (OsdIndex v = 0; v < base.GetNumVertices(); ++v) {
        if (base.GetVertexRule(v) != Sdc::Crease::RULE_CREASE || base.GetVertexSharpness(v) > 0) continue;
        bool three = false;
        for (OsdIndex f : base.GetVertexFaces(v)) three = three || sectorFaces(base, f, v) == 3;
        for (OsdIndex e : base.GetVertexEdges(v)) three = three && (isSharp(base, e) || base.GetEdgeSharpness(e) <= 0);
        if (three && sharpEdgeCount(base, v) == 2) runs.push_back(v);
    }
    return runs;
}

}  // namespace

double boundingBoxDiagonal(const std::vector<float>& positions) {
    if (positions.size() < 3) return 0;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i + 2 < positions.size(); i += 3)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], double(positions[i + size_t(k)]));
            hi[k] = std::max(hi[k], double(positions[i + size_t(k)]));
        }
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return std::sqrt(d2);
}

// --- OsdLimitSurface ---------------------------------------------------------------

struct OsdLimitSurface::Impl {
    // Without edits below level 0 (K = 0): the mesh's adaptive refiner, the patches
    // over its (level-0 edited) control points. With edits down to level K >= 1:
    // the uniform prefix to level K, and `refiner` is level K's adaptive refiner.
    EditedPrefix prefix;
    uint32_t edits = 0;
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<Far::PatchTable> patches;
    std::unique_ptr<Far::PatchMap> map;
    std::vector<Point> points;  // refined vertices, then the patch table's local points

    const Far::TopologyLevel& base() const {
        return prefix.depth > 0 ? prefix.uniform->GetLevel(0) : refiner->GetLevel(0);
    }
};

OsdLimitSurface::OsdLimitSurface() : impl_(new Impl) {}
OsdLimitSurface::~OsdLimitSurface() = default;

bool OsdLimitSurface::built() const { return impl_->map != nullptr; }
uint32_t OsdLimitSurface::editCount() const { return impl_->edits; }
int OsdLimitSurface::editLevel() const { return impl_->prefix.depth; }

Status OsdLimitSurface::build(const InputMesh& mesh, int isolation) {
    impl_.reset(new Impl);
    Impl& m = *impl_;
    std::vector<Point> control;
    if (Status st = checkEdits(mesh); !st) return st;
    if (mesh.editDepth() == 0) {
        if (Status st = oracleRefiner(mesh, "oracle", m.refiner); !st) return st;
        control = editedControlPoints(mesh);
    } else {
        if (Status st = buildEditedPrefix(mesh, m.prefix); !st) return st;
        Status st = oracleRefiner(m.prefix.last, "oracle (level " + std::to_string(m.prefix.depth) + ")", m.refiner);
        m.prefix.last = InputMesh{};
        if (!st) return st;
        control = std::move(m.prefix.points);
        m.prefix.points = {};
    }
    // Infinitely sharp features as OpenSubdiv's infinitely sharp patches, regular
    // patches with boundary rules, which need no isolation there: on a CAD part with
    // many sharp edges the PatchTable at isolation 10 is then hundreds of megabytes,
    // not gigabytes.
    Far::TopologyRefiner::AdaptiveOptions adaptive(isolation);
    adaptive.useInfSharpPatch = true;
    m.refiner->RefineAdaptive(adaptive);
    Far::PatchTableFactory::Options options(isolation);
    options.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
    options.SetPatchPrecision<double>();
    options.useInfSharpPatch = true;
    m.patches.reset(Far::PatchTableFactory::Create(*m.refiner, options));
    if (!m.patches) return Status::error(Status::Internal, "OpenSubdiv made no patch table");
    m.points = refinedPoints(*m.refiner, std::move(control));
    const size_t refined = m.points.size();
    m.points.resize(refined + size_t(m.patches->GetNumLocalPoints()));
    if (auto* local = m.patches->GetLocalPointStencilTable<double>())
        local->UpdateValues(m.points.data(), m.points.data() + refined);
    m.map.reset(new Far::PatchMap(*m.patches));
    m.edits = uint32_t(mesh.edits.size());
    return Status::ok();
}

bool OsdLimitSurface::evaluate(int face, double u, double v, double pos[3], double normal[3], double duOut[3],
                               double dvOut[3]) const {
    if (!built() || face < 0 || face >= impl_->base().GetNumFaces()) return false;
    // In a level-K sub-triangle: its parameters are (u, v) scaled by 2^K (and turned
    // by 180 degrees in rotated ones), so its normal is the base face's.
    if (impl_->prefix.depth > 0) face = locateSubface(*impl_->prefix.uniform, impl_->prefix.depth, face, u, v);
    const Far::PatchTable::PatchHandle* h = impl_->map->FindPatch(face, u, v);
    if (!h) return false;
    double w[20], wu[20], wv[20];
    impl_->patches->EvaluateBasis<double>(*h, u, v, w, wu, wv);
    const auto cvs = impl_->patches->GetPatchVertices(*h);
    double du[3] = {0, 0, 0}, dv[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) pos[k] = 0;
    for (int i = 0; i < cvs.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const double x = impl_->points[size_t(cvs[i])].p[k];
            pos[k] += w[i] * x;
            du[k] += wu[i] * x;
            dv[k] += wv[i] * x;
        }
    normal[0] = du[1] * dv[2] - du[2] * dv[1];
    normal[1] = du[2] * dv[0] - du[0] * dv[2];
    normal[2] = du[0] * dv[1] - du[1] * dv[0];
    const double len = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    for (int k = 0; k < 3; ++k) normal[k] = len > 0 ? normal[k] / len : 0.0;
    if (duOut) std::copy(du, du + 3, duOut);
    if (dvOut) std::copy(dv, dv + 3, dvOut);
    return true;
}

bool OsdLimitSurface::normalUndefined(int face, double u, double v) const {
    if (!built() || face < 0 || face >= impl_->base().GetNumFaces()) return false;
    const Far::TopologyLevel& base = impl_->base();
    const auto fv = base.GetFaceVertices(face);
    const double corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    for (int i = 0; i < 3; ++i) {
        if (u != corner[i][0] || v != corner[i][1]) continue;
        const OsdIndex x = fv[i];
        if (base.IsVertexNonManifold(x)) return true;
        if (base.IsVertexInfSharp(x) && sharpEdgeCount(base, x) < 2) return true;
        // A lasting sharp corner whose sector holds several faces; a crease or
        // boundary sector of six or more (Loop's interior modes there reach the
        // crease tangent's eigenvalue: no common plane, baker/src/limit.cpp).
        const int sharp = sharpEdgeCount(base, x), faces = sectorFaces(base, face, x);
        const bool corner = sharp >= 3 || (sharp >= 2 && base.IsVertexInfSharp(x));
        if (corner ? faces > 1 : faces >= 6) return true;
    }
    return false;
}

bool OsdLimitSurface::normalSignAmbiguous(int face, double u, double v) const {
    if (!built() || face < 0 || face >= impl_->base().GetNumFaces()) return false;
    const Far::TopologyLevel& base = impl_->base();
    const auto fv = base.GetFaceVertices(face);
    const double corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    for (int i = 0; i < 3; ++i) {
        if (u != corner[i][0] || v != corner[i][1]) continue;
        int semi = 0;  // semi-sharp edges
        for (OsdIndex e : base.GetVertexEdges(fv[i])) semi += !isSharp(base, e) && base.GetEdgeSharpness(e) > 0;
        const int sharp = sharpEdgeCount(base, fv[i]);
        return sharp >= 2 && (sharp + semi >= 3 || base.IsVertexInfSharp(fv[i]));
    }
    return false;
}

// --- OsdRefinedVertices ------------------------------------------------------------

struct OsdRefinedVertices::Impl {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::vector<Point> vertices;
    std::vector<size_t> levelStart;
};

OsdRefinedVertices::OsdRefinedVertices() : impl_(new Impl) {}
OsdRefinedVertices::~OsdRefinedVertices() = default;

Status OsdRefinedVertices::build(const InputMesh& mesh, int maxDepth) {
    impl_.reset(new Impl);
    if (Status st = oracleRefiner(mesh, "oracle", impl_->refiner); !st) return st;
    // Every three-face run isolated too: a superset of the baker's slit tips, so the
    // baker's vertices there have their match.
    OracleMesh runs = oracleMesh(mesh);
    runs.isolate = threeFaceRuns(impl_->refiner->GetLevel(0));
    if (!runs.isolate.empty()) {
        OsdErrors errors;
        impl_->refiner = oracleRefiner(runs, oracleOptions(mesh));
        if (!impl_->refiner || !errors.empty()) return errors.rejected("oracle");
    }
    // As the baker refines: every feature isolated to the full depth, infinitely
    // sharp creases included.
    Far::TopologyRefiner::AdaptiveOptions adaptive(maxDepth);
    adaptive.useInfSharpPatch = false;
    adaptive.considerFVarChannels = !runs.isolate.empty();
    impl_->refiner->RefineAdaptive(adaptive);
    impl_->vertices = refinedPoints(*impl_->refiner, controlPoints(mesh));
    size_t start = 0;
    for (int l = 0; l <= impl_->refiner->GetMaxLevel(); ++l) {
        impl_->levelStart.push_back(start);
        start += size_t(impl_->refiner->GetLevel(l).GetNumVertices());
    }
    return Status::ok();
}

int OsdRefinedVertices::levels() const { return int(impl_->levelStart.size()); }

const double* OsdRefinedVertices::vertex(int level, int vertex) const {
    return impl_->vertices[impl_->levelStart[size_t(level)] + size_t(vertex)].p;
}

int OsdRefinedVertices::vertexChild(int level, int parent) const {
    if (level < 1 || level >= levels()) return -1;
    const Far::TopologyLevel& up = impl_->refiner->GetLevel(level - 1);
    if (parent < 0 || parent >= up.GetNumVertices()) return -1;
    const OsdIndex c = up.GetVertexChildVertex(parent);
    return OpenSubdiv::Vtr::IndexIsValid(c) ? int(c) : -1;
}

int OsdRefinedVertices::edgeChild(int level, int a, int b) const {
    if (level < 1 || level >= levels()) return -1;
    const Far::TopologyLevel& up = impl_->refiner->GetLevel(level - 1);
    if (a < 0 || b < 0 || a >= up.GetNumVertices() || b >= up.GetNumVertices()) return -1;
    OsdIndex edge = -1;
    for (OsdIndex e : up.GetVertexEdges(a)) {
        const auto ends = up.GetEdgeVertices(e);
        if (ends[0] != b && ends[1] != b) continue;
        if (edge >= 0) return -1;  // two edges between a and b
        edge = e;
    }
    const OsdIndex c = edge >= 0 ? up.GetEdgeChildVertex(edge) : -1;
    return OpenSubdiv::Vtr::IndexIsValid(c) ? int(c) : -1;
}

namespace {

// Sdc's VERTEX interface on a vertex of a refined level.
class LevelVertex {
public:
    LevelVertex(const Far::TopologyLevel& level, OsdIndex v) : level_(level), v_(v) {}
    int GetNumEdges() const { return level_.GetVertexEdges(v_).size(); }
    int GetNumFaces() const { return level_.GetVertexFaces(v_).size(); }
    float GetSharpness() const { return level_.GetVertexSharpness(v_); }
    float* GetSharpnessPerEdge(float s[]) const {
        const auto edges = level_.GetVertexEdges(v_);
        for (int i = 0; i < edges.size(); ++i) s[i] = level_.GetEdgeSharpness(edges[i]);
        return s;
    }

private:
    const Far::TopologyLevel& level_;
    OsdIndex v_;
};

// The limit of a dart (an interior manifold vertex with one infinitely sharp edge),
// whose limit Sdc's smooth mask only approximates: its 1-ring refined in double
// until it has shrunk to the vertex. With d_i = r_i - v, edges in cyclic order and
// s the sharp one, Loop's rules give
//   v' = v + b sum_j d_j        (b: the smooth vertex rule's ring weight)
//   d'_i = d_i / 2 - b sum_j d_j                               (i = s: the midpoint)
//   d'_i = 3/8 d_i + 1/8 (d_i-1 + d_i+1) - b sum_j d_j         (otherwise)
// and the ring shrinks by the subdominant eigenvalue (below 0.7) each level.
void dartLimit(const Far::TopologyLevel& at, OsdIndex vertex, const double* q,
               const std::function<const double*(OsdIndex)>& point, double p[3]) {
    const auto edges = at.GetVertexEdges(vertex);
    const int n = edges.size();
    std::vector<double> d(3 * size_t(n)), next(d.size());
    int sharp = 0;
    double size = 0;
    for (int i = 0; i < n; ++i) {
        const auto ends = at.GetEdgeVertices(edges[i]);
        const double* r = point(ends[0] == vertex ? ends[1] : ends[0]);
        for (int k = 0; k < 3; ++k) d[3 * size_t(i) + size_t(k)] = r[k] - q[k], size += std::fabs(r[k] - q[k]);
        if (at.IsEdgeInfSharp(edges[i])) sharp = i;
    }
    const double c = 0.25 * std::cos(2.0 * M_PI / n) + 0.375, b = (0.625 - c * c) / n;
    std::copy(q, q + 3, p);
    for (int level = 0; level < 400 && size > 1e-19 * (std::fabs(p[0]) + std::fabs(p[1]) + std::fabs(p[2])); ++level) {
        double sum[3] = {0, 0, 0};
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) sum[k] += d[3 * size_t(i) + size_t(k)];
        for (int k = 0; k < 3; ++k) p[k] += b * sum[k];
        size = 0;
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) {
                const double di = d[3 * size_t(i) + size_t(k)];
                const double around =
                    d[3 * size_t((i + n - 1) % n) + size_t(k)] + d[3 * size_t((i + 1) % n) + size_t(k)];
                const double x = (i == sharp ? 0.5 * di : 0.375 * di + 0.125 * around) - b * sum[k];
                next[3 * size_t(i) + size_t(k)] = x;
                size += std::fabs(x);
            }
        d.swap(next);
    }
}

}  // namespace

bool OsdRefinedVertices::limitPosition(int level, int vertex, double p[3]) const {
    if (level < 0 || level >= levels() || vertex < 0 || vertex >= impl_->refiner->GetLevel(level).GetNumVertices())
        return false;
    for (;;) {
        const Far::TopologyLevel& at = impl_->refiner->GetLevel(level);
        bool stationary = !at.IsVertexSemiSharp(vertex);
        for (OsdIndex e : at.GetVertexEdges(vertex)) stationary = stationary && !at.IsEdgeSemiSharp(e);
        if (stationary && at.GetVertexRule(vertex) == Sdc::Crease::RULE_DART) {
            if (at.IsVertexNonManifold(vertex) || at.IsVertexBoundary(vertex)) return false;
            dartLimit(
                at, vertex, this->vertex(level, vertex), [&](OsdIndex r) { return this->vertex(level, int(r)); }, p);
            return true;
        }
        if (stationary) {
            const int n = at.GetVertexEdges(vertex).size();
            std::vector<double> ew(size_t(n) + 1, 0.0), fw(at.GetVertexFaces(vertex).size() + 1, 0.0);
            double vw = 0;
            SdcMask mask(&vw, ew.data(), fw.data());
            Sdc::Scheme<Sdc::SCHEME_LOOP>(impl_->refiner->GetSchemeOptions())
                .ComputeVertexLimitMask(LevelVertex(at, vertex), mask, at.GetVertexRule(vertex));
            const double* q = this->vertex(level, vertex);
            for (int k = 0; k < 3; ++k) p[k] = vw * q[k];
            for (int i = 0; i < mask.GetNumEdgeWeights(); ++i) {
                const auto ends = at.GetEdgeVertices(at.GetVertexEdges(vertex)[i]);
                const double* r = this->vertex(level, ends[0] == vertex ? ends[1] : ends[0]);
                for (int k = 0; k < 3; ++k) p[k] += ew[size_t(i)] * r[k];
            }
            return true;
        }
        vertex = vertexChild(level + 1, vertex);
        if (vertex < 0) return false;
        ++level;
    }
}

}  // namespace lt
