// tests/check/test_loopcheck.cpp -- loopcheck's checks one by one (check_internal.h):
// the bitwise weld and its edge counts on hand-made soups, the normals against their
// triangles, the Embree ray test on hand-made closed and holed spheres. The CLI:
// test_loopcheck_cli.cpp; every corpus asset passing: test_loopcheck_corpus.cpp.
#include "check_internal.h"  // looptess_check_internal

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace {

// --- hand-made soups ------------------------------------------------------------------

// Appends triangle (a, b, c); every vertex on base face 0 at an interior (u, v), so an
// open edge is never on the control mesh's boundary.
void triangle(lt::Tessellation& s, const float* a, const float* b, const float* c, bool sphereNormals) {
    const float* p[3] = {a, b, c};
    float n[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                  (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                  (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
    for (const float* v : p) {
        const float* src = sphereNormals ? v : n;
        const float len = std::sqrt(src[0] * src[0] + src[1] * src[1] + src[2] * src[2]);
        for (int k = 0; k < 3; ++k) s.positions.push_back(v[k]), s.normals.push_back(src[k] / len);
        s.face.push_back(0);
        s.uv.push_back(0.25f), s.uv.push_back(0.25f);
    }
}

lt::Tessellation tetrahedron() {
    const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    lt::Tessellation s;
    for (const auto& f : {std::array<int, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}})
        triangle(s, v[f[0]], v[f[1]], v[f[2]], false);
    return s;
}

// An octahedron split `levels` times, projected on the sphere of `radius`; CCW
// outwards, sphere normals. Midpoints are computed once per edge, so shared edges
// match bit for bit.
lt::Tessellation sphere(int levels, float radius) {
    std::vector<std::array<float, 3>> v = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    std::vector<std::array<uint32_t, 3>> f = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                              {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto m = [&](uint32_t a, uint32_t b) {
            auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            std::array<float, 3> p;
            for (int k = 0; k < 3; ++k) p[k] = 0.5f * (v[a][k] + v[b][k]);
            const float len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            for (float& x : p) x /= len;
            v.push_back(p);
            return mid[key] = uint32_t(v.size() - 1);
        };
        std::vector<std::array<uint32_t, 3>> next;
        for (const auto& t : f) {
            const uint32_t a = m(t[0], t[1]), b = m(t[1], t[2]), c = m(t[2], t[0]);
            next.insert(next.end(), {{t[0], a, c}, {a, t[1], b}, {c, b, t[2]}, {a, b, c}});
        }
        f = next;
    }
    lt::Tessellation s;
    for (auto& p : v)
        for (float& x : p) x *= radius;
    for (const auto& t : f) triangle(s, v[t[0]].data(), v[t[1]].data(), v[t[2]].data(), true);
    return s;
}

// A control topology of one drawn base face whose edges have kind `kind`.
lt::ControlTopology oneFace(uint8_t kind) {
    lt::ControlTopology t;
    t.drawn = {1};
    t.edgeKind = {kind, kind, kind};
    t.drawnFaces = 1;
    return t;
}

TEST(LoopcheckWeld, ClosedTetrahedronHasNoOpenEdges) {
    lt::WeldResult w;
    lt::weldTessellation(tetrahedron(), oneFace(lt::ControlTopology::kInterior), w);
    EXPECT_EQ(w.weldedVertices, 4u);
    EXPECT_EQ(w.edges, 6u);
    EXPECT_EQ(w.openEdges, 0u);
    EXPECT_EQ(w.nonManifoldEdges + w.misorientedEdges + w.degenerateTriangles, 0u);
    EXPECT_TRUE(w.pass());
}

TEST(LoopcheckWeld, OneUlpOpensEdges) {
    lt::Tessellation s = tetrahedron();
    s.positions[0] = std::nextafter(s.positions[0], 1.0f);  // vertex 0 of triangle 0 only
    lt::WeldResult w;
    lt::weldTessellation(s, oneFace(lt::ControlTopology::kInterior), w);
    EXPECT_EQ(w.weldedVertices, 5u);
    EXPECT_EQ(w.openEdges, 4u);  // the nudged triangle's two edges at the vertex, and their partners
    EXPECT_EQ(w.crackEdges, 4u);
    EXPECT_FALSE(w.pass());
}

TEST(LoopcheckWeld, MinusZeroWeldsWithPlusZero) {
    lt::Tessellation s = tetrahedron();
    s.positions[0] = -0.0f;  // the value 0 with the other sign bit
    lt::WeldResult w;
    lt::weldTessellation(s, oneFace(lt::ControlTopology::kInterior), w);
    EXPECT_EQ(w.openEdges, 0u);
}

// The edge table starts at twice the triangles, enough for a closed mesh (1.5
// edges a triangle), and grows for a soup of separate triangles (3): every edge is
// still counted once.
TEST(LoopcheckWeld, EveryEdgeCountsOnceHoweverManyTheTriangleHas) {
    lt::Tessellation apart;
    for (int i = 0; i < 2000; ++i) {
        const float x = float(i);
        const float a[3] = {x, 0, 0}, b[3] = {x + 0.5f, 0, 0}, c[3] = {x, 0.5f, 0};
        triangle(apart, a, b, c, false);
    }
    lt::WeldResult w;
    lt::weldTessellation(apart, oneFace(lt::ControlTopology::kInterior), w);
    EXPECT_EQ(w.weldedVertices, 6000u);
    EXPECT_EQ(w.edges, 6000u);
    EXPECT_EQ(w.openEdges, 6000u);
    lt::weldTessellation(sphere(5, 1.0f), oneFace(lt::ControlTopology::kInterior), w);
    EXPECT_EQ(w.edges, 3u * 8u * 1024u / 2u);  // 8 * 4^5 triangles
    EXPECT_EQ(w.openEdges, 0u);
    EXPECT_TRUE(w.pass());
}

TEST(LoopcheckWeld, OpenEdgesOnTheControlBoundaryAreExpected) {
    lt::Tessellation s;
    const float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    triangle(s, a, b, c, false);
    s.uv = {0, 0, 1, 0, 0, 1};  // the base face's corners
    lt::WeldResult w;
    lt::weldTessellation(s, oneFace(lt::ControlTopology::kBoundary), w);
    EXPECT_EQ(w.openEdges, 3u);
    EXPECT_EQ(w.boundaryEdges, 3u);
    EXPECT_EQ(w.crackEdges, 0u);
    EXPECT_TRUE(w.pass());
    lt::weldTessellation(s, oneFace(lt::ControlTopology::kInterior), w);
    EXPECT_EQ(w.crackEdges, 3u);
    EXPECT_FALSE(w.pass());
}

TEST(LoopcheckWeld, FindsATJunction) {
    // a-b is one edge of the upper triangle and two (a-m, m-b) of the lower ones.
    const float a[3] = {0, 0, 0}, b[3] = {2, 0, 0}, c[3] = {1, 1, 0}, m[3] = {1, 0, 0}, d[3] = {1, -1, 0};
    lt::Tessellation s;
    triangle(s, a, b, c, false);
    triangle(s, a, d, m, false);
    triangle(s, m, d, b, false);
    lt::WeldResult w;
    lt::weldTessellation(s, oneFace(lt::ControlTopology::kInterior), w);
    EXPECT_EQ(w.tJunctions, 1u);
    EXPECT_EQ(w.tJunctionVertices, 1u);
    EXPECT_EQ(w.openEdges, 7u);  // every edge but d-m is used once
}

TEST(LoopcheckWeld, DegenerateTrianglesAreSkipped) {
    lt::Tessellation s = tetrahedron();
    const float p[3] = {0, 0, 0}, q[3] = {1, 0, 0};
    triangle(s, p, p, q, false);
    lt::WeldResult w;
    lt::weldTessellation(s, oneFace(lt::ControlTopology::kInterior), w);
    EXPECT_EQ(w.degenerateTriangles, 1u);
    EXPECT_TRUE(w.pass());
}

// Three triangles on one edge, of base faces 0 and 1 (their control edges interior):
// the surface touching itself where both faces are folded back onto each other
// (W6, not a failure); else W2 fails it.
TEST(LoopcheckWeld, AnEdgeOfThreeTrianglesIsContactOnlyBetweenFoldedFaces) {
    const float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0, -1, 0}, e[3] = {0, 1, 1e-7f};
    lt::Tessellation s;
    triangle(s, a, b, c, false);
    triangle(s, b, a, d, false);
    triangle(s, a, b, e, false);
    s.face = {0, 0, 0, 0, 0, 0, 1, 1, 1};
    lt::ControlTopology t;
    t.drawn = {1, 1};
    t.edgeKind.assign(6, lt::ControlTopology::kInterior);
    t.drawnFaces = 2;
    for (const std::vector<uint8_t>& folded : {std::vector<uint8_t>{}, {1, 0}, {0, 1}, {1, 1}}) {
        t.folded = folded;
        lt::WeldResult w;
        lt::weldTessellation(s, t, w);
        const bool contact = folded == std::vector<uint8_t>{1, 1};
        EXPECT_EQ(w.nonManifoldEdges, 1u);
        EXPECT_EQ(w.contactEdges, contact ? 1u : 0u);
        EXPECT_EQ(w.unexpectedNonManifoldEdges, contact ? 0u : 1u);  // (the other edges are cracks here)
    }
}

// Four triangles on one edge of a face that is not folded: the tessellation's fault
// (W2) while they all face one way; where two face the other way the limit surface
// folds there and its sheets meet in float (W6; holodeck at F = 64).
TEST(LoopcheckWeld, AnEdgeWhereTheSurfaceFoldsIsContact) {
    const float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0, -1, 0}, e[3] = {0.5f, 1, 0},
                f[3] = {0.5f, -1, 0};
    for (bool folds : {false, true}) {
        lt::Tessellation s;
        triangle(s, a, b, c, false);  // +z
        triangle(s, b, a, d, false);  // +z
        if (folds) {                  // a sheet folded back over the first two: -z
            triangle(s, b, a, e, false);
            triangle(s, a, b, f, false);
        } else {  // the same side again: +z
            triangle(s, a, b, e, false);
            triangle(s, b, a, f, false);
        }
        lt::WeldResult w;
        lt::weldTessellation(s, oneFace(lt::ControlTopology::kInterior), w);
        EXPECT_EQ(w.nonManifoldEdges, 1u);
        EXPECT_EQ(w.contactEdges, folds ? 1u : 0u);
        EXPECT_EQ(w.unexpectedNonManifoldEdges, folds ? 0u : 1u);
    }
}

// --- Embree rays on hand-made spheres ----------------------------------------------------

lt::CheckSettings raySettings() {
    lt::CheckSettings s;
    s.rays = 20000;
    s.rayOrigins = 200;
    return s;
}

std::unique_ptr<lt::RayScene> scene(const lt::Tessellation& soup) {
    auto mesh = std::make_shared<lt::WeldedMesh>();
    lt::WeldResult w;
    lt::weldTessellation(soup, oneFace(lt::ControlTopology::kInterior), w, mesh.get());
    std::unique_ptr<lt::RayScene> out;
    const lt::Status st = lt::RayScene::create(mesh, out);
    EXPECT_TRUE(st) << st.message;
    return out;
}

// N1 (checkNormals): sphere normals sit in front of every triangle; normals flipped
// over a triangle, or one zeroed, are found and named; a triangle whose corner normals
// disagree widely (a lone flipped corner among them) or a sliver is not judged.
TEST(LoopcheckNormals, FindsNormalsBehindTheirTriangleAndZeroNormals) {
    lt::Tessellation s = sphere(2, 1.0f);
    lt::NormalResult n;
    lt::checkNormals(s, n);
    EXPECT_TRUE(n.pass()) << n.firstFailure;
    EXPECT_EQ(n.judged, s.triangleCount());
    for (size_t i = 3 * 6; i < 3 * 9; ++i) s.normals[i] = -s.normals[i];  // triangle 2's corners
    lt::checkNormals(s, n);
    EXPECT_EQ(n.against, 3u);
    EXPECT_EQ(n.zero, 0u);
    EXPECT_NE(n.firstFailure.find("vertex 6, face 0"), std::string::npos) << n.firstFailure;
    for (size_t i = 3 * 6; i < 3 * 8; ++i) s.normals[i] = -s.normals[i];  // only vertex 8 stays flipped
    lt::checkNormals(s, n);
    EXPECT_EQ(n.against, 0u);
    EXPECT_EQ(n.unjudged, 1u);
    for (size_t i = 3 * 8; i < 3 * 9; ++i) s.normals[i] = -s.normals[i];
    for (int k = 0; k < 3; ++k) s.normals[3 * 7 + k] = 0.0f;  // vertex 7
    lt::checkNormals(s, n);
    EXPECT_EQ(n.against, 0u);
    EXPECT_EQ(n.zero, 1u);
    EXPECT_FALSE(n.pass());
    // A sliver (longest edge 1e4 times its altitude) with normals 1 degree apart.
    lt::Tessellation sliver;
    const float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0.5f, 1e-4f, 0};
    triangle(sliver, a, b, c, false);
    sliver.normals[0] = 0.017f;
    lt::checkNormals(sliver, n);
    EXPECT_EQ(n.judged, 0u);
    EXPECT_EQ(n.unjudged, 1u);
    EXPECT_TRUE(n.pass());
}

// A plane drawn with one triangle turned over (kenney_alien at F = 3.3: a coarse
// triangle where the surface's parameterization bends hard in its plane): every
// normal is +z, right for the plane; the turned triangle's own plane faces -z. It is
// counted as folded, not as a normal behind its triangle; the same triangle alone (no
// neighbour turns it over) is judged and fails.
TEST(LoopcheckNormals, ATriangleTheDrawnSurfaceTurnsOverIsNotJudged) {
    //   d ------ c          a b c, a c d: counter-clockwise, facing +z
    //   |  \    / |         b e c: clockwise (its plane faces -z), its corners'
    //   |   \  /  |         normals +z; it shares edge b-c with a b c
    //   a -- b -- e
    const float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {1, 1, 0}, d[3] = {0, 1, 0}, e[3] = {2, 0, 0};
    lt::Tessellation s;
    triangle(s, a, b, c, false);
    triangle(s, a, c, d, false);
    triangle(s, b, c, e, false);                                    // wound clockwise in the plane: geometric normal -z
    for (int k = 0; k < 3; ++k) s.normals[3 * (6 + k) + 2] = 1.0f;  // its corners' normals +z, as the plane's
    lt::NormalResult n;
    lt::checkNormals(s, n);
    EXPECT_TRUE(n.pass()) << n.firstFailure;
    EXPECT_EQ(n.folded, 1u);
    EXPECT_EQ(n.judged, 2u);
    lt::Tessellation alone;
    triangle(alone, b, c, e, false);
    for (int k = 0; k < 3; ++k) alone.normals[3 * k + 2] = 1.0f;
    lt::checkNormals(alone, n);
    EXPECT_EQ(n.folded, 0u);
    EXPECT_EQ(n.against, 3u);
    EXPECT_FALSE(n.pass());
}

TEST(LoopcheckRays, NoRayEscapesAClosedSphere) {
    auto s = scene(sphere(3, 1.0f));
    ASSERT_TRUE(s);
    lt::RayResult r;
    ASSERT_TRUE(lt::castRays(*s, nullptr, 2.0 * std::sqrt(3.0), raySettings(), 1, r));
    ASSERT_TRUE(r.ran) << r.skipped;
    EXPECT_EQ(r.rays, 20000u);
    EXPECT_EQ(r.origins, 200u);
    EXPECT_EQ(r.escaped, 0u);
    EXPECT_EQ(r.frontHits, 0u);
}

// Far from unit size Embree's robust traversal lost rays: at a radius of 1e15 or 1e18
// hundreds of 2,000 escaped this closed sphere, at 1e-19 no point counted as inside,
// and on a box of side 1e15 the walk counting a probe's winding number never ended
// (loopcheck --rays ran for hours). The scene is traced scaled by a power of two.
TEST(LoopcheckRays, NoRayEscapesASphereFarFromUnitSize) {
    for (float scale : {1e-19f, 1e-15f, 1e13f, 1e15f, 1e18f}) {
        SCOPED_TRACE(scale);
        lt::Tessellation soup = sphere(3, 1.0f);
        for (float& x : soup.positions) x *= scale;
        auto s = scene(soup);
        ASSERT_TRUE(s);
        lt::RayResult r;
        lt::CheckSettings settings = raySettings();
        settings.rays = 2000;
        ASSERT_TRUE(lt::castRays(*s, nullptr, 2.0 * std::sqrt(3.0) * double(scale), settings, 1, r));
        EXPECT_TRUE(r.ran) << r.skipped;
        EXPECT_EQ(r.origins, 200u);
        EXPECT_EQ(r.escaped, 0u);
    }
}

TEST(LoopcheckRays, RaysEscapeThroughAMissingTriangle) {
    lt::Tessellation soup = sphere(3, 1.0f);
    for (auto* v : {&soup.positions, &soup.normals}) v->erase(v->begin(), v->begin() + 9);  // triangle 0
    soup.face.erase(soup.face.begin(), soup.face.begin() + 3);
    soup.uv.erase(soup.uv.begin(), soup.uv.begin() + 6);
    auto s = scene(soup);
    ASSERT_TRUE(s);
    lt::RayResult r;
    ASSERT_TRUE(lt::castRays(*s, nullptr, 2.0 * std::sqrt(3.0), raySettings(), 1, r));
    ASSERT_TRUE(r.ran) << r.skipped;
    EXPECT_GT(r.escaped, 0u);
    EXPECT_FALSE(r.pass());
}

// A closed surface wound inside out (every triangle turned over; at a pinch, a part
// turned over against the rest): its inside has winding number -1, and rays from
// there all hit it. Before, an origin was interior when its probes' first hits were
// backs, which held only for points outside the sphere whose 8 probes all went
// towards it, and most rays from those escaped: R1, on a closed surface without a
// crack (two generated pinch meshes at F = 3.3 and 8, 23 and 96 rays of 100000).
TEST(LoopcheckRays, NoRayEscapesASphereWoundInsideOut) {
    lt::Tessellation soup = sphere(3, 1.0f);
    for (size_t t = 0; t < soup.triangleCount(); ++t)
        for (int c = 0; c < 3; ++c)
            std::swap(soup.positions[9 * t + 3 + size_t(c)], soup.positions[9 * t + 6 + size_t(c)]);
    auto s = scene(soup);
    ASSERT_TRUE(s);
    lt::RayResult r;
    ASSERT_TRUE(lt::castRays(*s, nullptr, 2.0 * std::sqrt(3.0), raySettings(), 1, r));
    ASSERT_TRUE(r.ran) << r.skipped;
    EXPECT_EQ(r.origins, 200u);
    EXPECT_EQ(r.escaped, 0u);
    EXPECT_EQ(r.frontHits, r.rays);  // R5 says it is inside out
}

TEST(LoopcheckRays, HitDistancesAgreeWithAFinerSphereOnly) {
    auto reference = scene(sphere(5, 1.0f));
    auto coarse = scene(sphere(3, 1.0f));
    auto wrong = scene(sphere(3, 1.1f));
    ASSERT_TRUE(reference && coarse && wrong);
    const double diagonal = 2.0 * std::sqrt(3.0);
    lt::RayResult r;
    ASSERT_TRUE(lt::castRays(*coarse, reference.get(), diagonal, raySettings(), 1, r));
    EXPECT_TRUE(r.distanceChecked);
    EXPECT_EQ(r.compared, r.rays);
    EXPECT_EQ(r.distanceFailures, 0u) << "worst " << r.maxToleranceRatio << "x the tolerance";
    ASSERT_TRUE(lt::castRays(*wrong, reference.get(), diagonal, raySettings(), 1, r));
    EXPECT_GT(r.distanceFailures, r.compared / 2);
}

// Rays that first hit a front face (a displaced surface overlapping itself, as fandisk
// with --crease-angle 40 and a 2% map does at F = 5) make "inside" ambiguous: the
// findings say so, and an escape without an open edge says it may not be a crack.
TEST(LoopcheckFindings, FrontFaceHitsExplainEscapes) {
    lt::CheckReport report;
    report.structureValid = true;
    lt::TessellationChecks t;
    t.name = "F=5 equal displaced";
    t.path = "cpu";
    t.rays.ran = true;
    t.rays.rays = 3000;
    t.rays.frontHits = 13;
    report.tessellations = {t};
    lt::addFindings(lt::CheckSettings{}, report);
    ASSERT_EQ(report.findings.size(), 1u);
    EXPECT_EQ(report.findings[0].id, "R5");
    EXPECT_EQ(report.findings[0].severity, "info");
    EXPECT_NE(report.findings[0].text.find("13 of 3000 rays first hit a front face"), std::string::npos);
    report.tessellations[0].rays.escaped = 2;
    lt::addFindings(lt::CheckSettings{}, report);
    ASSERT_EQ(report.findings.size(), 1u);
    EXPECT_EQ(report.findings[0].id, "R1");
    EXPECT_EQ(report.findings[0].severity, "error");
    EXPECT_NE(report.findings[0].text.find("no open edge"), std::string::npos) << report.findings[0].text;
    EXPECT_EQ(lt::exitCode(report), 3);
}

}  // namespace
