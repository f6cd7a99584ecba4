// tests/runtime/test_tangents.cpp -- TANGENT on the limit surface: each
// sampled vertex's tangent against finite differences of OpenSubdiv's limit
// positions along the direction in which TEXCOORD_0's s grows (the face's (u,v)
// step d(u,v)/ds), brought into the vertex's tangent plane; its handedness w against
// the same differences along t. Where a regular patch is evaluated the tangent is
// the surface's own derivative; at IPP corners it comes from the flat IPP triangle's
// edges (spec "Tangents"), so it may be off by the triangle's turn, and those are
// held to a bound of their own.
#include "osd_reference.h"
#include "sanitizer.h"

#include "looptess/tools/baker.h"
#include "looptess/tools/osd_reference.h"
#include "looptess/runtime.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <tuple>

namespace lt {
namespace {

using Key = std::tuple<uint32_t, uint32_t, uint32_t>;  // face, u bits, v bits

Key keyOf(uint32_t face, float u, float v) {
    uint32_t a, b;
    std::memcpy(&a, &u, 4);
    std::memcpy(&b, &v, 4);
    return {face, a, b};
}

// What an IPP corner's tangent comes from (cpu_evaluate.cpp's cornerDerivatives).
enum class Corner { Regular, Extraordinary, Explicit };

// (face, u, v) of every IPP corner drawn at `depth` (emit()'s mapping), and its kind:
// a smooth stencil of 6 neighbours or of another number, or explicit weights.
std::map<Key, Corner> ippCorners(const Asset& asset, uint32_t depth) {
    std::map<Key, Corner> out;
    const float corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    const LimitStencils& ls = asset.levels[depth].limit;
    for (const IrregularFace& f : asset.levels[depth].irregular)
        for (int c = 0; c < 3; ++c) {
            const float d = std::ldexp(1.0f, -int(f.param.level)), sign = f.param.rotated ? -1.0f : 1.0f;
            const Key key = keyOf(f.param.baseFace, d * (float(f.param.ui) + sign * corner[c][0]),
                                  d * (float(f.param.vi) + sign * corner[c][1]));
            const uint32_t st = f.corners[c];
            out[key] = std::binary_search(ls.masked.begin(), ls.masked.end(), st) ? Corner::Explicit
                       : ls.start[st + 1] - ls.start[st] == 6                     ? Corner::Regular
                                                                                  : Corner::Extraordinary;
        }
    return out;
}

double angleBetween(const double a[3], const double b[3]) {
    double c = 0, la = 0, lb = 0;
    for (int k = 0; k < 3; ++k) {
        c += a[k] * b[k];
        la += a[k] * a[k];
        lb += b[k] * b[k];
    }
    return std::acos(std::max(-1.0, std::min(1.0, c / std::sqrt(la * lb))));
}

// dP along the (u,v) direction `dir` at (u,v) of `face`, by differences of the limit
// surface: central where both steps stay on the face, else one-sided into it.
bool difference(const OsdLimitSurface& osd, int face, double u, double v, const double dir[2], double out[3]) {
    const double h = 1e-4 / std::sqrt(dir[0] * dir[0] + dir[1] * dir[1]);
    auto inside = [](double a, double b) { return a >= 0 && b >= 0 && a + b <= 1; };
    double lo = -h, hi = h;
    if (!inside(u + hi * dir[0], v + hi * dir[1])) hi = 0;
    if (!inside(u + lo * dir[0], v + lo * dir[1])) lo = 0;
    if (hi == lo) return false;
    double p0[3], p1[3], n[3];
    if (!osd.evaluate(face, u + lo * dir[0], v + lo * dir[1], p0, n) ||
        !osd.evaluate(face, u + hi * dir[0], v + hi * dir[1], p1, n))
        return false;
    for (int k = 0; k < 3; ++k) out[k] = (p1[k] - p0[k]) / (hi - lo);
    return true;
}

struct Figures {
    size_t compared = 0, count[3] = {0, 0, 0}, handedness = 0;
    double worst[3] = {0, 0, 0};  // by Corner; Regular also counts every patch point
};

// Every 1/20000th vertex of `mesh`'s CPU tessellation at `factor`, and every IPP
// corner, against the differences.
Figures compare(const char* name, const InputMesh& mesh, float factor) {
    Figures f;
    Asset asset;
    OsdLimitSurface osd;
    if (!bake(mesh, BakeSettings{}, asset) || !osd.build(mesh)) return f;
    EvalSettings settings;
    settings.tessFactor = factor;
    Tessellation soup;
    evaluateCpu(asset, asset.positions.data(), settings, soup);
    EXPECT_EQ(soup.tangents.size(), soup.vertexCount() * 4);
    const std::map<Key, Corner> ipp = ippCorners(asset, runtimeDepth(asset, factor));
    const size_t step = std::max<size_t>(1, soup.vertexCount() / 20000);
    for (size_t i = 0; i < soup.vertexCount(); ++i) {
        const uint32_t face = soup.face[i];
        const auto at = ipp.find(keyOf(face, soup.uv[2 * i], soup.uv[2 * i + 1]));
        if (i % step != 0 && at == ipp.end()) continue;
        const float* c = &mesh.faceUVs[6 * size_t(face)];
        const double s1 = c[2] - c[0], t1 = c[3] - c[1], s2 = c[4] - c[0], t2 = c[5] - c[1];
        const double det = s1 * t2 - s2 * t1;
        if (std::fabs(det) < 1e-12) continue;  // degenerate UVs: no direction of s
        const double alongS[2] = {t2 / det, -t1 / det}, alongT[2] = {-s2 / det, s1 / det};
        double ps[3], pt[3];
        const double u = soup.uv[2 * i], v = soup.uv[2 * i + 1];
        if (!difference(osd, int(face), u, v, alongS, ps) || !difference(osd, int(face), u, v, alongT, pt)) continue;
        const float* n = &soup.normals[3 * i];
        double along = 0;
        for (int k = 0; k < 3; ++k) along += n[k] * ps[k];
        double expected[3], ours[3];
        for (int k = 0; k < 3; ++k) {
            expected[k] = ps[k] - n[k] * along;
            ours[k] = soup.tangents[4 * i + size_t(k)];
        }
        const int kind = int(at == ipp.end() ? Corner::Regular : at->second);
        f.worst[kind] = std::max(f.worst[kind], angleBetween(expected, ours));
        ++f.count[kind];
        ++f.compared;
        // Handedness: cross(normal, tangent) * w points along t's differences.
        const double* x = ours;
        const double b[3] = {n[1] * x[2] - n[2] * x[1], n[2] * x[0] - n[0] * x[2], n[0] * x[1] - n[1] * x[0]};
        const double w = soup.tangents[4 * i + 3];
        f.handedness += kind != int(Corner::Explicit) && (w == 1.0 || w == -1.0) &&
                        w * (b[0] * pt[0] + b[1] * pt[1] + b[2] * pt[2]) > 0;
    }
    std::printf(
        "[ figures  ] %s F=%g: %zu tangents against differences, worst %.3g rad; at IPP corners on %zu "
        "extraordinary vertices %.3g, on %zu with explicit weights %.3g; handedness right at %zu\n",
        name, factor, f.compared, f.worst[0], f.count[1], f.worst[1], f.count[2], f.worst[2], f.handedness);
    return f;
}

// Smooth: every tangent is the surface's derivative along s, within the differences'
// error; at extraordinary vertices within 0.05 radians of one-sided differences
// along s from the vertex (no derivative there: a convention, spec "Tangents").
TEST(Tangents, FollowTheTexcoordsOnTheLimitSurface) {
    const InputMesh mesh = test::loadObj(std::string(LOOPTESS_TEST_DATA) + "/spot.obj");
    ASSERT_FALSE(mesh.faceUVs.empty());
    for (float factor : test::asanSample(std::vector<float>{8.0f, 1.0f}, 2)) {  // ASan: F = 8 alone
        SCOPED_TRACE(factor);
        const Figures f = compare("spot", mesh, factor);
        EXPECT_GT(f.compared, 300u);
        EXPECT_GT(f.count[int(Corner::Extraordinary)], 50u);
        EXPECT_EQ(f.count[int(Corner::Explicit)], 0u);
        EXPECT_EQ(f.handedness, f.compared);
        EXPECT_LT(f.worst[int(Corner::Regular)], 1e-3);
        EXPECT_LT(f.worst[int(Corner::Extraordinary)], 0.05);
    }
}

// Creases: regular patches on either side of a sharp edge (phantom points) are as
// exact; IPP corners with explicit weights take the flat triangle's edges, which is
// only an approximation (its figure is reported, not held).
TEST(Tangents, BesideCreases) {
    if (test::kAsan) GTEST_SKIP() << "release build only (the smooth case runs under ASan)";
    InputMesh mesh = test::loadObj(std::string(LOOPTESS_TEST_DATA) + "/spot.obj");
    addCreasesByAngle(mesh, 25);
    const Figures f = compare("spot --crease-angle 25", mesh, 8.0f);
    EXPECT_GT(f.count[int(Corner::Explicit)], 50u);
    EXPECT_EQ(f.handedness, f.compared - f.count[int(Corner::Explicit)]);
    EXPECT_LT(f.worst[int(Corner::Regular)], 1e-3);
    EXPECT_LT(f.worst[int(Corner::Extraordinary)], 0.05);
}

}  // namespace
}  // namespace lt
