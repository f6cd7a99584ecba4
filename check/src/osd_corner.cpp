// OsdCornerNormals (looptess/tools/osd_reference.h).
#include "looptess/tools/osd_reference.h"
#include "looptess/tools/osd.h"

#include "osd_topology.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

namespace lt {
namespace {

using Point = OsdPoint;

// The faces around one vertex: a mesh of its own.
struct Patch {
    std::vector<Point> points;
    OracleMesh mesh;           // no holes
    int vertex = 0, face = 0;  // the corner: its vertex, the face followed
};

// The faces of `level` around `vertex`, with their points, sharpness and the
// face of them that holds `face`.
Patch around(const Far::TopologyLevel& level, const std::vector<Point>& points, int vertex, int face) {
    Patch p;
    std::map<int, int> local;
    auto at = [&](int v) {
        auto [it, added] = local.emplace(v, int(p.points.size()));
        if (added) p.points.push_back(points[size_t(v)]);
        return it->second;
    };
    p.vertex = at(vertex);
    for (int f : level.GetVertexFaces(vertex)) {
        if (f == face) p.face = int(p.mesh.triangles.size() / 3);
        auto fv = level.GetFaceVertices(f);
        auto fe = level.GetFaceEdges(f);
        for (int i = 0; i < 3; ++i) p.mesh.triangles.push_back(at(fv[i]));
        for (int i = 0; i < 3; ++i) {
            float s = level.GetEdgeSharpness(fe[i]);
            if (s > 0) p.mesh.sharp[edgeKey(at(fv[i]), at(fv[(i + 1) % 3]))] = s;
        }
    }
    if (float s = level.GetVertexSharpness(vertex); s > 0) p.mesh.corners[p.vertex] = s;
    p.mesh.vertices = int(p.points.size());
    // Refinement is affine: move the vertex to the origin, its ring to unit size.
    const Point c = p.points[size_t(p.vertex)];
    double big = 0;
    for (Point& q : p.points)
        for (int k = 0; k < 3; ++k) big = std::max(big, std::fabs(q.p[k] -= c.p[k]));
    for (Point& q : p.points)
        for (double& x : q.p) x /= big > 0 ? big : 1.0;
    return p;
}

// No semi-sharp sharpness left around the corner: until then the normal may stand
// still for a while (a flat face beside a semi-sharp edge) and turn later.
bool stationary(const Patch& p) {
    auto fixed = [](float s) { return s <= 0 || s >= 10; };
    for (const auto& [e, s] : p.mesh.sharp)
        if (!fixed(s)) return false;
    for (const auto& [v, s] : p.mesh.corners)
        if (!fixed(s)) return false;
    return true;
}

void cross(const double a[3], const double b[3], double n[3]) {
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
}

// Below this sine of its angle at the vertex a corner triangle has no area to
// trust (double precision), as the baker's authored side (baker/src/orient.h).
constexpr double kAreaSine = 1e-9;

double norm(const double a[3]) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// The corner triangle's normal (unit) and the sine of its angle at the vertex.
double cornerTriangle(const Patch& p, double n[3]) {
    const int* f = &p.mesh.triangles[size_t(p.face) * 3];
    int at = 0;
    while (f[at] != p.vertex) ++at;
    const double* o = p.points[size_t(f[at])].p;
    const double* a = p.points[size_t(f[(at + 1) % 3])].p;
    const double* b = p.points[size_t(f[(at + 2) % 3])].p;
    double da[3], db[3];
    for (int k = 0; k < 3; ++k) {
        da[k] = a[k] - o[k];
        db[k] = b[k] - o[k];
    }
    cross(da, db, n);
    double len = norm(n), sine = len / (norm(da) * norm(db));
    for (int k = 0; k < 3; ++k) n[k] /= len > 0 ? len : 1.0;
    return sine;
}

}  // namespace

struct OsdCornerNormals::Impl {
    Sdc::Options options;
    std::unique_ptr<Far::TopologyRefiner> refiner;  // level 0 only: OpenSubdiv's sharpness
    std::vector<Point> points;
    std::map<std::tuple<uint32_t, int, int, int>, Result> done;  // (face, corner, maxLevels, drawnLevels)
};

OsdCornerNormals::OsdCornerNormals() : impl_(new Impl) {}
OsdCornerNormals::~OsdCornerNormals() = default;
bool OsdCornerNormals::built() const { return impl_->refiner != nullptr; }

Status OsdCornerNormals::build(const InputMesh& mesh) {
    impl_.reset(new Impl);
    impl_->options = oracleOptions(mesh);
    // The whole mesh, so OpenSubdiv decides its sharpness (non-manifold edges
    // become infinitely sharp) as it does for the whole mesh; holes are not followed.
    Patch whole;
    whole.mesh = oracleMesh(mesh);
    whole.mesh.holes.clear();
    for (size_t i = 0; i < mesh.vertexCount(); ++i)
        whole.points.push_back({{mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]}});
    impl_->refiner = oracleRefiner(whole.mesh, impl_->options);
    if (!impl_->refiner) return Status::error(Status::BadInput, "corner oracle: OpenSubdiv rejected the mesh");
    impl_->points = std::move(whole.points);
    return Status::ok();
}

bool OsdCornerNormals::normal(uint32_t face, int corner, int maxLevels, int drawnLevels, Result& out) const {
    out = Result{};
    const Far::TopologyLevel& base = impl_->refiner->GetLevel(0);
    if (int(face) >= base.GetNumFaces() || corner < 0 || corner > 2) return false;
    const auto key = std::make_tuple(face, corner, maxLevels, drawnLevels);
    if (auto it = impl_->done.find(key); it != impl_->done.end()) {
        out = it->second;
        return true;
    }
    if (!refine(face, corner, maxLevels, drawnLevels, out)) return false;
    impl_->done.emplace(key, out);
    return true;
}

bool OsdCornerNormals::refine(uint32_t face, int corner, int maxLevels, int drawnLevels, Result& out) const {
    const Far::TopologyLevel& base = impl_->refiner->GetLevel(0);
    Patch p = around(base, impl_->points, base.GetFaceVertices(int(face))[corner], int(face));
    double n[3], last[3];
    const double first = cornerTriangle(p, last);
    // The triangle's normal at each drawn level (0 .. drawnLevels) that has an area,
    // for the side it is drawn on (spec "The side").
    std::vector<std::array<double, 3>> drawn;
    if (first >= kAreaSine) drawn.push_back({last[0], last[1], last[2]});
    // A face k steps around the vertex reaches the followed face's corner triangle at
    // level k: until every face of the ring has, a still normal proves nothing (a
    // flat face beside a curved ring keeps its plane's normal for a few levels).
    const int reach = int(p.mesh.triangles.size() / 3);
    for (out.levels = 1; out.levels <= maxLevels; ++out.levels) {
        std::unique_ptr<Far::TopologyRefiner> r = oracleRefiner(p.mesh, impl_->options);
        if (!r) return false;
        Far::TopologyRefiner::UniformOptions uniform(1);
        uniform.fullTopologyInLastLevel = true;
        r->RefineUniform(uniform);
        const Far::TopologyLevel& parent = r->GetLevel(0);
        const Far::TopologyLevel& child = r->GetLevel(1);
        std::vector<Point> points(size_t(child.GetNumVertices()));
        Point* src = p.points.data();
        Point* dst = points.data();
        Far::PrimvarRefinerReal<double>(*r).Interpolate(1, src, dst);
        int v = parent.GetVertexChildVertex(p.vertex), f = -1;
        for (int c : parent.GetFaceChildFaces(p.face))
            for (int x : child.GetFaceVertices(c))
                if (x == v) f = c;
        if (f < 0) return false;
        Patch next = around(child, points, v, f);
        if (cornerTriangle(next, n) < kAreaSine) {  // too thin to trust
            out.degenerate = out.levels == 1 && first < 1e-9;
            break;
        }
        p = std::move(next);
        if (out.levels <= drawnLevels) drawn.push_back({n[0], n[1], n[2]});
        double c[3];
        cross(n, last, c);
        out.lastStep = std::atan2(norm(c), n[0] * last[0] + n[1] * last[1] + n[2] * last[2]);
        std::copy(n, n + 3, last);
        // (A flat sector's normal stands still until it turns over: never stop
        // before the drawn levels are seen.)
        if (out.levels >= std::max(reach, drawnLevels) && out.lastStep < 1e-9 && stationary(p)) break;
    }
    out.levels = std::min(out.levels, maxLevels);
    int along = 0, against = 0;
    for (const auto& m : drawn) (m[0] * last[0] + m[1] * last[1] + m[2] * last[2] < 0 ? against : along) += 1;
    const bool turn = drawnLevels >= 0 &&
                      (against > along || (against == along && !drawn.empty() &&
                                           drawn[0][0] * last[0] + drawn[0][1] * last[1] + drawn[0][2] * last[2] < 0));
    for (int k = 0; k < 3; ++k) out.normal[k] = turn ? -last[k] : last[k];
    return true;
}

}  // namespace lt
