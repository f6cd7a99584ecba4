// tests/runtime/test_patterns.cpp -- refinement patterns (runtime/internal/patterns.h) against
// their definition: every pattern of edge factors 1..64 tiles the domain triangle
// (positive areas summing to 1/2, each inner edge shared by two triangles in
// opposite directions, each boundary edge used once), edge k carries exactly the
// points j / e_k, and a uniform pattern is the uniform grid; and at a power-of-two
// global factor a mesh draws exactly uniform refinement's triangle count.
#include "patterns.h"

#include "looptess/tools/baker.h"
#include "looptess/runtime.h"
#include "osd_reference.h"  // loadObj, corpusMesh
#include "sanitizer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

namespace lt::test {
namespace {

TEST(Patterns, FactorsRoundUpToPowersOfTwo) {
    EXPECT_EQ(patternFactor(0.3f), 1u);
    EXPECT_EQ(patternFactor(1.0f), 1u);
    EXPECT_EQ(patternFactor(1.01f), 2u);
    EXPECT_EQ(patternFactor(8.0f), 8u);
    EXPECT_EQ(patternFactor(8.5f), 16u);
    EXPECT_EQ(patternFactor(1000.0f), 64u);
    EXPECT_EQ(patternFactor(NAN), 1u);
}

TEST(Patterns, EveryPatternTilesTheTriangleWithTheEdgesPoints) {
    const uint32_t kFactors[] = {1, 2, 4, 8, 16, 32, 64};
    size_t patterns = 0;
    std::map<std::array<uint32_t, 3>, std::pair<size_t, size_t>> sizes;  // points, triangles
    for (uint32_t e0 : kFactors)
        for (uint32_t e1 : kFactors)
            for (uint32_t e2 : kFactors) {
                const uint32_t e[3] = {e0, e1, e2};
                SCOPED_TRACE(std::to_string(e0) + " " + std::to_string(e1) + " " + std::to_string(e2));
                TessDomain d;
                makePattern(e, d);
                const float* c = d.coords.data();
                double area = 0;
                std::map<std::pair<uint32_t, uint32_t>, int> directed;
                for (size_t t = 0; t < d.triangleCount(); ++t) {
                    const uint32_t* v = &d.triangles[3 * t];
                    const double ax = c[3 * v[0]], ay = c[3 * v[0] + 1], bx = c[3 * v[1]], by = c[3 * v[1] + 1],
                                 cx = c[3 * v[2]], cy = c[3 * v[2] + 1];
                    const double a = 0.5 * ((bx - ax) * (cy - ay) - (cx - ax) * (by - ay));
                    ASSERT_GT(a, 0.0) << "triangle " << t;
                    area += a;
                    for (int k = 0; k < 3; ++k) ++directed[{v[k], v[(k + 1) % 3]}];
                }
                EXPECT_EQ(area, 0.5);
                // Inner edges twice (once each way), boundary edges once; and the
                // boundary's points: edge k at exactly j / e_k.
                std::set<float> onEdge[3];
                for (auto& [edge, uses] : directed) {
                    ASSERT_EQ(uses, 1);
                    if (directed.count({edge.second, edge.first})) continue;
                    const float* p = &c[3 * edge.first];
                    const float* q = &c[3 * edge.second];
                    const int k = p[0] == 0 && q[0] == 0   ? 0
                                  : p[1] == 0 && q[1] == 0 ? 1
                                  : p[2] == 0 && q[2] == 0 ? 2
                                                           : -1;
                    ASSERT_GE(k, 0) << "an unshared edge inside the triangle";
                    onEdge[k].insert(k == 0 ? p[1] : p[0]);
                    onEdge[k].insert(k == 0 ? q[1] : q[0]);
                }
                for (int k = 0; k < 3; ++k) {
                    std::set<float> expected;
                    for (uint32_t j = 0; j <= e[k]; ++j) expected.insert(float(j) / float(e[k]));
                    EXPECT_EQ(onEdge[k], expected) << "edge " << k;
                }
                if (e0 == e1 && e1 == e2) {
                    EXPECT_EQ(d.triangleCount(), size_t(e0) * e0);
                    EXPECT_EQ(d.pointCount(), size_t(e0 + 1) * (e0 + 2) / 2);
                }
                sizes[{e0, e1, e2}] = {d.pointCount(), d.triangleCount()};
                ++patterns;
            }
    EXPECT_EQ(patterns, 343u);
    // No larger for smaller factors: so the uniform factors of a bound F size every
    // screen-space frame under it (VulkanSurface::evaluateSizes).
    size_t pairs = 0;
    for (const auto& [e, size] : sizes)
        for (const auto& [f, bigger] : sizes)
            if (e[0] <= f[0] && e[1] <= f[1] && e[2] <= f[2]) {
                EXPECT_LE(size.first, bigger.first)
                    << e[0] << " " << e[1] << " " << e[2] << " <= " << f[0] << " " << f[1] << " " << f[2];
                EXPECT_LE(size.second, bigger.second)
                    << e[0] << " " << e[1] << " " << e[2] << " <= " << f[0] << " " << f[1] << " " << f[2];
                ++pairs;
            }
    EXPECT_EQ(pairs, 21952u);  // (28 ordered pairs of exponents a <= b)^3
}

// A torus of 8 x 6 quads, each cut by the same diagonal: every vertex has valence 6,
// so every face is a regular patch of level 0. At F = 2^k patterns draw F^2
// triangles a face, uniform refinement's level k.
InputMesh regularTorus() {
    InputMesh m;
    const int nu = 8, nv = 6;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double a = 2 * M_PI * i / nu, b = 2 * M_PI * j / nv, r = 1 + 0.4 * std::cos(b);
            m.positions.insert(m.positions.end(),
                               {float(r * std::cos(a)), float(r * std::sin(a)), float(0.4 * std::sin(b))});
        }
    auto at = [&](int i, int j) { return uint32_t((i % nu) * nv + (j % nv)); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            m.faces.insert(m.faces.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.faces.insert(m.faces.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

// F^2 triangles a base face at F = 2^k: on the torus (regular patches only, any
// F up to 64) and on spot (extraordinary vertices: split patches drawn whole, one
// flat IPP triangle per irregular face of level k = log2 F, F <= 2^maxDepth).
TEST(Patterns, APowerOfTwoFactorDrawsUniformRefinementsTriangles) {
    struct Case {
        std::string name;
        InputMesh mesh;
        std::vector<uint32_t> factors;
    };
    // Under ASan the smaller factors only (F = 64 on the torus and 8 on spot: 760 k triangles).
    const Case cases[] = {
        {"torus", regularTorus(), kAsan ? std::vector<uint32_t>{1, 8} : std::vector<uint32_t>{1, 2, 8, 64}},
        {"spot", loadObj(corpusMesh("spot.obj")),
         kAsan ? std::vector<uint32_t>{1, 4} : std::vector<uint32_t>{1, 2, 4, 8}}};
    for (const Case& c : cases) {
        InputMesh mesh = c.mesh;
        ASSERT_TRUE(checkInput(mesh, c.name));
        Asset asset;
        BakeSettings settings;
        settings.maxDepth = 3;
        ASSERT_TRUE(bake(mesh, settings, asset));
        for (uint32_t f : c.factors) {
            EvalSettings es;
            es.tessFactor = float(f);
            es.path = DrawPath::Patterns;
            Tessellation soup;
            evaluateCpu(asset, asset.positions.data(), es, soup);
            EXPECT_EQ(soup.triangleCount(), size_t(asset.faceCount()) * f * f) << c.name << " at F = " << f;
        }
    }
}

// EvalSettings::indexed: each pattern point once per patch, the same vertices as the
// soup bit for bit once the indices are followed (global and screen-space factors).
TEST(Patterns, IndexedEvaluationIsTheSoupWithSharedPoints) {
    for (const std::string& path :
         {corpusMesh("spot.obj"), std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop/loop_cubes_semisharp.obj"}) {
        InputMesh mesh = loadObj(path);
        ASSERT_TRUE(checkInput(mesh, path));
        Asset asset;
        BakeSettings settings;
        settings.maxDepth = 3;
        ASSERT_TRUE(bake(mesh, settings, asset));
        for (int screen = 0; screen < 2; ++screen)
            for (float f : kAsan ? std::vector<float>{3.0f} : std::vector<float>{1.0f, 3.0f, 8.0f}) {
                SCOPED_TRACE(path + " F = " + std::to_string(f) + (screen ? " screen" : ""));
                EvalSettings es;
                es.tessFactor = f;
                es.path = DrawPath::Patterns;
                if (screen) es.lod = Lod{LodMode::Screen, {3, 2, 4}, 300, 4};
                Tessellation soup, indexed;
                evaluateCpu(asset, asset.positions.data(), es, soup);
                es.indexed = true;
                evaluateCpu(asset, asset.positions.data(), es, indexed);
                ASSERT_EQ(indexed.triangleCount(), soup.triangleCount());
                if (f > 1) { EXPECT_LT(indexed.vertexCount(), soup.vertexCount()); }  // F = 1: one triangle a patch
                size_t differ = 0;
                for (size_t k = 0; k < indexed.indices.size(); ++k) {
                    const uint32_t v = indexed.indices[k];
                    differ += std::memcmp(&soup.positions[3 * k], &indexed.positions[3 * v], 12) != 0 ||
                              std::memcmp(&soup.normals[3 * k], &indexed.normals[3 * v], 12) != 0 ||
                              std::memcmp(&soup.uv[2 * k], &indexed.uv[2 * v], 8) != 0 ||
                              soup.face[k] != indexed.face[v];
                }
                EXPECT_EQ(differ, 0u);
            }
    }
}

}  // namespace
}  // namespace lt::test
