// Embree ray tests on a welded tessellation (check_internal.h, RayScene and castRays).
#include "check_internal.h"

#include "random.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <mutex>

namespace lt {
namespace {

// Largest coordinates from 2^(kLeastExponent - 1) to 2^kMostExponent are ray traced as
// they are (RayScene::Impl).
constexpr int kLeastExponent = -16, kMostExponent = 24;

// One Embree device shared by every live scene; released with the last of them.
struct Device {
    RTCDevice device = nullptr;
    ~Device() {
        if (device) rtcReleaseDevice(device);
    }
};

std::shared_ptr<Device> acquireDevice(std::string& error) {
    static std::mutex mutex;
    static std::weak_ptr<Device> shared;
    std::lock_guard<std::mutex> lock(mutex);
    if (auto d = shared.lock()) return d;
    auto d = std::make_shared<Device>();
    d->device = rtcNewDevice(nullptr);
    if (!d->device) {
        error = "Embree: rtcNewDevice failed (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")";
        return nullptr;
    }
    shared = d;
    return d;
}

struct Hit {
    bool hit = false;
    float t = 0, u = 0, v = 0;  // u, v: the barycentrics of corners 1 and 2
    uint32_t prim = 0;
};

// The unit CCW normal of triangle `prim` (outwards for a closed, CCW mesh).
void faceNormal(const WeldedMesh& m, uint32_t prim, double n[3]) {
    const float* p[3];
    for (int k = 0; k < 3; ++k) p[k] = &m.positions[3 * size_t(m.triangles[3 * size_t(prim) + size_t(k)])];
    double e1[3], e2[3];
    for (int c = 0; c < 3; ++c) e1[c] = double(p[1][c]) - p[0][c], e2[c] = double(p[2][c]) - p[0][c];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int c = 0; c < 3; ++c) n[c] = len > 0 ? n[c] / len : 0.0;
}

double distance(const double a[3], const double b[3]) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Squared distance from p to triangle (a, b, c): the closest point lies in the
// Voronoi region of a corner, of an edge, or inside the face.
double distance2ToTriangle(const double p[3], const double a[3], const double b[3], const double c[3]) {
    auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int k = 0; k < 3; ++k)
        ab[k] = b[k] - a[k], ac[k] = c[k] - a[k], ap[k] = p[k] - a[k], bp[k] = p[k] - b[k], cp[k] = p[k] - c[k];
    double q[3];
    auto point = [&](const double* o, const double* d1, double s1, const double* d2, double s2) {
        for (int k = 0; k < 3; ++k) q[k] = o[k] + s1 * (d1 ? d1[k] : 0) + s2 * (d2 ? d2[k] : 0);
    };
    const double d1 = dot(ab, ap), d2 = dot(ac, ap), d3 = dot(ab, bp), d4 = dot(ac, bp), d5 = dot(ab, cp),
                 d6 = dot(ac, cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    double bc[3];
    for (int k = 0; k < 3; ++k) bc[k] = c[k] - b[k];
    if (d1 <= 0 && d2 <= 0)
        point(a, nullptr, 0, nullptr, 0);
    else if (d3 >= 0 && d4 <= d3)
        point(b, nullptr, 0, nullptr, 0);
    else if (d6 >= 0 && d5 <= d6)
        point(c, nullptr, 0, nullptr, 0);
    else if (vc <= 0 && d1 >= 0 && d3 <= 0)
        point(a, ab, d1 / (d1 - d3), nullptr, 0);
    else if (vb <= 0 && d2 >= 0 && d6 <= 0)
        point(a, ac, d2 / (d2 - d6), nullptr, 0);
    else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        point(b, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)), nullptr, 0);
    else
        point(a, ab, vb / (va + vb + vc), ac, vc / (va + vb + vc));
    double d2sum = 0;
    for (int k = 0; k < 3; ++k) d2sum += (p[k] - q[k]) * (p[k] - q[k]);
    return d2sum;
}

struct NearestQuery {
    const WeldedMesh* mesh;
    double p[3];
    double scale;  // RayScene::Impl's
    double best2 = INFINITY;
    uint32_t prim = 0;
};

bool nearestTriangle(RTCPointQueryFunctionArguments* args) {
    NearestQuery& q = *static_cast<NearestQuery*>(args->userPtr);
    double v[3][3];
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
            v[k][c] =
                q.mesh->positions[3 * size_t(q.mesh->triangles[3 * size_t(args->primID) + size_t(k)]) + size_t(c)];
    const double d2 = distance2ToTriangle(q.p, v[0], v[1], v[2]);
    if (!(d2 < q.best2)) return false;
    q.best2 = d2;
    q.prim = args->primID;
    args->query->radius = float(std::sqrt(d2) * q.scale);
    return true;
}

}  // namespace

// Embree sees the mesh scaled by `scale`, a power of two that brings its largest
// coordinate to [0.5, 1) when it is far from 1 (else 1, the mesh's own positions
// shared): exact, so welded vertices stay welded. Embree's robust traversal is
// good near unit size: unscaled, hundreds of 2,000 rays escaped a closed sphere of
// radius 1e15, and no point counted as inside one of radius 1e-19. Rays and
// distances are scaled on the way in and back: callers see the mesh's own units.
struct RayScene::Impl {
    std::shared_ptr<Device> device;
    std::shared_ptr<const WeldedMesh> mesh;
    float scale = 1;
    std::vector<float> scaled;  // the positions times scale, when it is not 1
    RTCScene scene = nullptr;
    ~Impl() {
        if (scene) rtcReleaseScene(scene);
    }
    Hit trace(const float o[3], const float d[3], float tnear = 0.0f) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        rh.ray.org_x = o[0] * scale, rh.ray.org_y = o[1] * scale, rh.ray.org_z = o[2] * scale;
        rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
        rh.ray.tnear = tnear * scale;
        rh.ray.tfar = INFINITY;
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        Hit h;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
        h.hit = true;
        h.t = rh.ray.tfar / scale;
        h.u = rh.hit.u, h.v = rh.hit.v;
        h.prim = rh.hit.primID;
        return h;
    }
    // Distance from p to the nearest triangle, and that triangle (`prim`).
    double nearest(const double p[3], uint32_t& prim) const {
        NearestQuery q{mesh.get(), {p[0], p[1], p[2]}, double(scale)};
        RTCPointQuery query;
        query.x = float(p[0] * scale), query.y = float(p[1] * scale), query.z = float(p[2] * scale);
        query.time = 0;
        query.radius = INFINITY;
        RTCPointQueryContext context;
        rtcInitPointQueryContext(&context);
        rtcPointQuery(scene, &query, &context, nearestTriangle, &q);
        prim = q.prim;
        return std::sqrt(q.best2);
    }
    // The surface's winding number around `o`, counted along the whole ray: +1
    // for each crossing through a triangle's back (leaving), -1 through a front
    // (entering). 0 outside; 1 inside a closed surface wound outwards, -1 inside
    // a part wound inside out. Hits within `step` of the last one are one crossing
    // (a ray through an edge may hit both its triangles).
    //
    //    o --->|  )  |--->      first hit a back (|): inside by the first hit
    //          A  B  A          alone, yet 0 when B, a part wound inside out, is
    //                           crossed twice the other way: o is outside A
    //
    // Each next start is past the last hit by `step` and past the last start by one
    // float at least, and a ray meets a plane once: a walk of more hits than
    // triangles has gone wrong (on a box of side 1e15 traced unscaled one never
    // ended) and counts 0, as if outside (not an origin).
    int winding(const float o[3], const float d[3], float step) const {
        int sum = 0;
        float start = 0;
        for (size_t hits = 0;; ++hits) {
            const Hit h = trace(o, d, start);
            if (!h.hit) return sum;
            if (hits == mesh->triangleCount()) return 0;
            double n[3];
            faceNormal(*mesh, h.prim, n);
            sum += n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0 ? 1 : -1;
            start = std::max({h.t + step, std::nextafter(h.t, INFINITY), std::nextafter(start, INFINITY)});
        }
    }
};

RayScene::RayScene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RayScene::~RayScene() = default;
const WeldedMesh& RayScene::mesh() const { return *impl_->mesh; }

Status RayScene::create(std::shared_ptr<const WeldedMesh> mesh, std::unique_ptr<RayScene>& out) {
    auto impl = std::make_unique<Impl>();
    std::string error;
    impl->device = acquireDevice(error);
    if (!impl->device) return Status::error(Status::Internal, error);
    impl->mesh = std::move(mesh);
    const WeldedMesh& m = *impl->mesh;
    RTCDevice device = impl->device->device;
    impl->scene = rtcNewScene(device);
    // Compact: triangles by index, not copied (on an 8 M-triangle grid the build took
    // 36 bytes a triangle instead of 96, in half the time; a ray 1.5 times as long).
    rtcSetSceneFlags(impl->scene, RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT));
    if (m.triangleCount() > 0) {
        float largest = 0;
        for (float x : m.positions) largest = std::max(largest, std::fabs(x));
        int exponent = 0;
        std::frexp(largest, &exponent);
        if (std::isfinite(largest) && largest > 0 && (exponent < kLeastExponent || exponent > kMostExponent)) {
            impl->scale = std::ldexp(1.0f, -exponent);
            impl->scaled.resize(m.positions.size());
            for (size_t i = 0; i < m.positions.size(); ++i) impl->scaled[i] = m.positions[i] * impl->scale;
        }
        const float* positions = impl->scaled.empty() ? m.positions.data() : impl->scaled.data();
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions, 0,
                                   3 * sizeof(float), m.vertexCount());
        rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.triangles.data(), 0,
                                   3 * sizeof(uint32_t), m.triangleCount());
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(impl->scene, geometry);
        rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(impl->scene);
    if (RTCError e = rtcGetDeviceError(device); e != RTC_ERROR_NONE)
        return Status::error(Status::Internal,
                             "Embree: building the scene failed (error " + std::to_string(int(e)) + ")");
    out.reset(new RayScene(std::move(impl)));
    return Status::ok();
}

Status castRays(const RayScene& test, const RayScene* reference, double diagonal, const CheckSettings& settings,
                uint64_t seed, RayResult& out, double displacementSlack, const RayParameters* parameters) {
    out = RayResult{};
    const WeldedMesh& m = test.mesh();
    const TriangleBound testBound = parameters ? parameters->testBound : TriangleBound{};
    auto bound = [&](uint32_t prim) {
        const double b = double(m.chordBound[prim]);
        return testBound ? std::max(b, testBound(prim)) : b;
    };
    if (m.triangleCount() == 0 || settings.rays == 0 || !(diagonal > 0)) {
        out.skipped = m.triangleCount() == 0 ? "no triangles" : settings.rays == 0 ? "--rays 0" : "empty bounding box";
        return Status::ok();
    }
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < 3 * m.vertexCount(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], double(m.positions[i]));
        hi[i % 3] = std::max(hi[i % 3], double(m.positions[i]));
    }
    Random rng(seed);
    auto randomDirection = [&](float d[3]) {
        double x[3];
        rng.direction(x);
        for (int c = 0; c < 3; ++c) d[c] = float(x[c]);
    };
    // Interior points.
    const uint64_t want = std::max<uint64_t>(1, std::min<uint64_t>(settings.rayOrigins, settings.rays));
    const uint64_t maxCandidates = 64 * want;
    std::vector<float> origins;
    while (origins.size() / 3 < want && out.candidates < maxCandidates) {
        double p[3];
        if (out.candidates++ % 2 == 0) {
            for (int c = 0; c < 3; ++c) p[c] = lo[c] + (hi[c] - lo[c]) * rng.uniform();
        } else {
            const uint32_t prim = uint32_t(rng.below(m.triangleCount()));
            const double r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
            const double w[3] = {1 - r1, r1 * (1 - r2), r1 * r2};
            double n[3];
            faceNormal(m, prim, n);
            const double depth = diagonal * std::pow(10.0, -4.0 + 2.5 * rng.uniform());
            for (int c = 0; c < 3; ++c) {
                p[c] = -n[c] * depth;
                for (int k = 0; k < 3; ++k)
                    p[c] += w[k] * m.positions[3 * size_t(m.triangles[3 * size_t(prim) + size_t(k)]) + size_t(c)];
            }
        }
        // Interior: every probe ray, on both surfaces, counts one winding number,
        // not 0. The first hit alone (a back: leaving) took points outside a part
        // wound inside out for interior ones, and rays from them escaped (R1).
        const float o[3] = {float(p[0]), float(p[1]), float(p[2])};
        const float step = float(1e-7 * diagonal);
        int winding = 0;
        bool inside = true;
        for (uint32_t k = 0; k < settings.originProbes && inside; ++k) {
            float d[3];
            randomDirection(d);
            const int w = test.impl().winding(o, d, step);
            if (k == 0) winding = w;
            inside = w != 0 && w == winding && (!reference || reference->impl().winding(o, d, step) == w);
        }
        if (inside) origins.insert(origins.end(), o, o + 3);
    }
    out.origins = origins.size() / 3;
    if (out.origins == 0) {
        out.skipped =
            "no interior point among " + std::to_string(out.candidates) + " candidates (a flat or inside-out surface?)";
        return Status::ok();
    }
    out.ran = true;
    out.distanceChecked = reference != nullptr;
    const double slack = settings.distanceSlack * diagonal + displacementSlack;
    for (uint64_t r = 0; r < settings.rays; ++r) {
        const float* o = &origins[3 * size_t(r % out.origins)];
        float d[3];
        randomDirection(d);
        ++out.rays;
        const Hit h = test.impl().trace(o, d);
        if (!h.hit) {
            ++out.escaped;
            continue;
        }
        double n[3];
        faceNormal(m, h.prim, n);
        const double cosine = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
        out.frontHits += cosine <= 0;
        if (!reference) continue;
        const Hit g = reference->impl().trace(o, d);
        if (!g.hit) {
            ++out.referenceEscaped;
            continue;
        }
        double nr[3];
        faceNormal(reference->mesh(), g.prim, nr);
        const double cr = std::fabs(nr[0] * d[0] + nr[1] * d[1] + nr[2] * d[2]);
        const double br = double(reference->mesh().chordBound[g.prim]);
        auto toleranceFor = [&](double b) {
            return (b + slack) / std::max(std::fabs(cosine), 1e-9) + (br + slack) / std::max(cr, 1e-9);
        };
        const double err = std::fabs(double(h.t) - double(g.t));
        // testBound only widens: it is asked only when the chord bound is not enough.
        double b = double(m.chordBound[h.prim]), tolerance = toleranceFor(b);
        if (!(err <= tolerance) && testBound) b = bound(h.prim), tolerance = toleranceFor(b);
        ++out.compared;
        if (!(err <= tolerance)) {
            // Past a fold (a ray grazing a ridge) one surface's exit can jump far
            // along the ray: then each hit point must lie on the other surface.
            double p[3], q[3];
            for (int c = 0; c < 3; ++c)
                p[c] = double(o[c]) + double(h.t) * d[c], q[c] = double(o[c]) + double(g.t) * d[c];
            bool onBoth = false;
            if (parameters && parameters->test && parameters->reference) {
                // At the hit's own (face, u, v) on the other surface: the tested point is
                // within b of the surface there, the reference's within its bound of it.
                const SurfaceIndex &ti = *parameters->test, &ri = *parameters->reference;
                uint32_t face = 0, other = 0;
                double x[2], at[3];
                onBoth = ti.parameters(h.prim, h.u, h.v, face, x) && ri.pointAt(face, x, other, at) &&
                         distance(p, at) <= b + double(reference->mesh().chordBound[other]) + 2 * slack;
                onBoth = onBoth && ri.parameters(g.prim, g.u, g.v, face, x) && ti.pointAt(face, x, other, at) &&
                         distance(q, at) <= br + bound(other) + 2 * slack;
            } else {  // without parameters, the nearest triangles stand in
                uint32_t np = 0, nq = 0;
                const double dp = reference->impl().nearest(p, np), dq = test.impl().nearest(q, nq);
                onBoth =
                    dp <= b + double(reference->mesh().chordBound[np]) + 2 * slack && dq <= br + bound(nq) + 2 * slack;
            }
            out.foldRays += onBoth;
            out.distanceFailures += !onBoth;
            if (onBoth) continue;
        }
        out.maxDistanceError = std::max(out.maxDistanceError, err / diagonal);
        out.maxToleranceRatio = std::max(out.maxToleranceRatio, err / tolerance);
    }
    return Status::ok();
}

}  // namespace lt
