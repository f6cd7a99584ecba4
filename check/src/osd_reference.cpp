// OpenSubdiv oracle (looptess/osd_reference.h).
#include "looptess/osd_reference.h"

#include "osd_edits.h"  // the uniform prefix of an edited mesh; includes the baker's refine.h

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <cmath>

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

} // namespace

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
        if (Status st = buildRefiner(mesh, isolation, "oracle", m.refiner, nullptr, SharpEdges::Patches); !st) return st;
        control = editedControlPoints(mesh);
    } else {
        if (Status st = buildEditedPrefix(mesh, m.prefix); !st) return st;
        Status st = buildRefiner(m.prefix.last, isolation, "oracle (level " + std::to_string(m.prefix.depth) + ")",
                                 m.refiner, nullptr, SharpEdges::Patches);
        m.prefix.last = InputMesh{};
        if (!st) return st;
        control = std::move(m.prefix.points);
        m.prefix.points = {};
    }
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
    if (Status st = buildRefiner(mesh, maxDepth, "oracle", impl_->refiner); !st) return st;
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

} // namespace lt
