// test_displacement.cpp -- displacement maps on the CPU: the runtime sampler
// (runtime/internal/displacement.h) is bitwise identical from every face on shared
// edges and corners, exact at grid points and linear in between; the baker's
// resampling (lt::bakeDisplacement) reads the map the right way up and welds seams.
//
// Assets: two triangles sharing an edge, in all 9 combinations of corner rotations
// (so the shared edge is every pair of face edges, in both directions) with a UV
// seam along it, and spot (tests/data/spot.obj, which has UVs), each with a map of
// the procedural pattern of displacement_map.h.
#include "looptess/tools/baker.h"

#include "displacement.h"
#include "displacement_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace {

using lt::Asset;

const std::string kSpot = std::string(LOOPTESS_TEST_DATA) + "/spot.obj";

uint32_t bitsOf(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

lt::InputMesh readObj(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    lt::InputMesh mesh;
    const lt::Status st = lt::parseObj(text, path, lt::InputOptions{}, mesh);
    EXPECT_TRUE(st) << st.message;
    return mesh;
}

Asset bakeMesh(const lt::InputMesh& mesh, const std::string& name) {
    Asset asset;
    lt::Status st = lt::checkInput(mesh, name);
    lt::BakeSettings settings;
    settings.maxDepth = 1;  // the map does not depend on the depth
    if (st) st = lt::bake(mesh, settings, asset);
    EXPECT_TRUE(st) << name << ": " << st.message;
    return asset;
}

// Triangles (0 1 3) and (1 2 3) of the unit square, corners rotated by ra and rb;
// face 0's UVs in the texture's left half, face 1's in the right half: a seam
// along the shared edge (1, 3).
lt::InputMesh twoFaces(int ra, int rb) {
    lt::InputMesh m;
    m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint32_t tri[2][3] = {{0, 1, 3}, {1, 2, 3}};
    const int rot[2] = {ra, rb};
    for (int f = 0; f < 2; ++f)
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = tri[f][(k + rot[f]) % 3];
            m.faces.push_back(v);
            m.faceUVs.push_back(0.05f + 0.4f * m.positions[3 * v] + 0.5f * float(f));
            m.faceUVs.push_back(0.1f + 0.8f * m.positions[3 * v + 1]);
        }
    return m;
}

lt::GrayImage patternImage(uint32_t size) {
    lt::GrayImage image;
    image.width = image.height = size;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) image.texels.push_back(lt::test::patternTexel(x, y, size, size));
    return image;
}

// `asset` with the pattern baked in at resolution R (0: the default).
Asset withMap(Asset asset, uint32_t R, uint32_t mapSize = 256) {
    lt::DisplacementSettings ds;
    ds.scale = 0.375f;
    ds.bias = -0.125f;
    ds.resolution = R;
    const lt::Status st = lt::bakeDisplacement(patternImage(mapSize), ds, asset, "test");
    EXPECT_TRUE(st) << st.message;
    if (st) {
        const lt::Status valid = lt::validateAsset(asset, "test");
        EXPECT_TRUE(valid) << valid.message;
    }
    return asset;
}

const Asset& spot() {
    static const Asset asset = bakeMesh(readObj(kSpot), "spot.obj");
    return asset;
}

// The decoded displacement of stored sample q: scale * (q * K) + bias.
float decoded(const Asset& a, uint64_t index) {
    return a.displacement.scale * (float(a.displacement.values[index]) * lt::kUnorm16) + a.displacement.bias;
}

const float kCorner[3][2] = {{0, 0}, {1, 0}, {0, 1}};

// Parameters along an edge: every m / 1024, and 16.16 fixed-point values like the
// tessellator's (k * 2^-16 for scattered k), with their mirror images.
std::vector<float> edgeParameters() {
    std::vector<float> t;
    for (int m = 0; m <= 1024; ++m) t.push_back(std::ldexp(float(m), -10));
    for (uint32_t k = 1; k < 65536; k += 977) {
        t.push_back(std::ldexp(float(k), -16));
        t.push_back(1.0f - std::ldexp(float(k), -16));
    }
    return t;
}

struct EdgeCheck {
    size_t points = 0, compared = 0, mismatches = 0;
    std::string first;
};

// (a): every point of every control-mesh edge, sampled from every face that has
// the edge, at the parameters above: the same bits from all of them.
EdgeCheck checkSharedEdges(const Asset& a) {
    const lt::DisplacementMap& m = a.displacement;
    std::map<uint32_t, std::vector<std::pair<uint32_t, int>>> uses;  // edge -> (face, face edge)
    for (uint32_t f = 0; f < a.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) uses[m.faceEdges[3 * f + k]].push_back({f, k});
    EdgeCheck check;
    const std::vector<float> params = edgeParameters();
    for (const auto& [edge, faces] : uses) {
        const uint32_t* c0 = &a.faces[3 * size_t(faces[0].first)];
        const uint32_t lo = std::min(c0[faces[0].second], c0[(faces[0].second + 1) % 3]);
        for (float t : params) {
            ++check.points;
            uint32_t reference = 0;
            for (size_t n = 0; n < faces.size(); ++n) {
                const auto [f, k] = faces[n];
                const uint32_t* c = &a.faces[3 * size_t(f)];
                const int from = c[k] == lo ? k : (k + 1) % 3, to = c[k] == lo ? (k + 1) % 3 : k;
                // lo + t (hi - lo) in the face's (u, v): exact for these t.
                const float u = (1.0f - t) * kCorner[from][0] + t * kCorner[to][0];
                const float v = (1.0f - t) * kCorner[from][1] + t * kCorner[to][1];
                const uint32_t bits = bitsOf(lt::sampleDisplacement(a, f, u, v));
                if (n == 0) {
                    reference = bits;
                    continue;
                }
                ++check.compared;
                if (bits != reference && check.mismatches++ == 0)
                    check.first = "edge " + std::to_string(edge) + " t " + std::to_string(t) + ": face " +
                                  std::to_string(faces[0].first) + " vs face " + std::to_string(f);
            }
        }
    }
    return check;
}

// (b): every corner of every face gives its control vertex's sample, exactly.
size_t checkCorners(const Asset& a) {
    size_t bad = 0;
    for (uint32_t f = 0; f < a.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) {
            const float d = lt::sampleDisplacement(a, f, kCorner[k][0], kCorner[k][1]);
            bad += bitsOf(d) != bitsOf(decoded(a, a.faces[3 * size_t(f) + k]));
        }
    return bad;
}

// (c): every grid point of every tile gives its sample exactly (interior, edge and
// corner points alike).
size_t checkGridPoints(const Asset& a) {
    const uint32_t R = a.displacement.resolution;
    size_t bad = 0;
    for (uint32_t f = 0; f < a.faceCount(); ++f)
        for (uint32_t j = 0; j <= R; ++j)
            for (uint32_t i = 0; i + j <= R; ++i) {
                const float d = lt::sampleDisplacement(a, f, float(i) / float(R), float(j) / float(R));
                bad += bitsOf(d) != bitsOf(decoded(a, lt::displacementSample(a, f, i, j)));
            }
    return bad;
}

void expectConsistent(const Asset& a, const std::string& name) {
    SCOPED_TRACE(name + " at resolution " + std::to_string(a.displacement.resolution));
    const EdgeCheck edges = checkSharedEdges(a);
    EXPECT_EQ(edges.mismatches, 0u) << edges.mismatches << " of " << edges.compared << "; first: " << edges.first;
    EXPECT_GT(edges.compared, 0u);
    EXPECT_EQ(checkCorners(a), 0u);
    EXPECT_EQ(checkGridPoints(a), 0u);
}

TEST(DisplacementSampler, TwoFacesEveryOrientationAndResolution) {
    for (int ra = 0; ra < 3; ++ra)
        for (int rb = 0; rb < 3; ++rb) {
            const Asset base = bakeMesh(twoFaces(ra, rb), "two faces");
            for (uint32_t R : {1u, 2u, 4u, 8u, 64u})
                expectConsistent(withMap(base, R), "rotations " + std::to_string(ra) + ", " + std::to_string(rb));
        }
}

TEST(DisplacementSampler, SpotSharedEdgesAndCorners) {
    for (uint32_t R : {4u, 16u}) expectConsistent(withMap(spot(), R), "spot");
}

// (c): inside a tile the value is the barycentric interpolation of the grid
// triangle's three samples (checked in double at pseudo-random points), and it
// approaches the edge values continuously.
TEST(DisplacementSampler, InteriorIsPiecewiseLinear) {
    const Asset a = withMap(spot(), 8);
    const uint32_t R = 8;
    uint32_t state = 12345;
    auto next = [&]() { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1 << 24); };
    double worst = 0;
    for (int n = 0; n < 20000; ++n) {
        const uint32_t f = uint32_t(next() * float(a.faceCount())) % a.faceCount();
        float u = next(), v = next();
        if (u + v >= 1.0f) {
            u = 1.0f - u;
            v = 1.0f - v;
        }
        if (u == 0.0f || v == 0.0f || u + v >= 1.0f) continue;
        const double x = double(u) * R, y = double(v) * R;
        const uint32_t i = uint32_t(x), j = uint32_t(y);
        const double fx = x - i, fy = y - j;
        auto q = [&](uint32_t gi, uint32_t gj) {
            return double(a.displacement.values[lt::displacementSample(a, f, gi, gj)]);
        };
        const double Q = fx + fy > 1 ? (fx + fy - 1) * q(i + 1, j + 1) + (1 - fx) * q(i, j + 1) + (1 - fy) * q(i + 1, j)
                                     : (1 - fx - fy) * q(i, j) + fx * q(i + 1, j) + fy * q(i, j + 1);
        const double expected = double(a.displacement.scale) * Q / 65535.0 + double(a.displacement.bias);
        worst = std::max(worst, std::fabs(double(lt::sampleDisplacement(a, f, u, v)) - expected));
    }
    EXPECT_LT(worst, 1e-6) << "largest difference from the barycentric interpolation";

    // Towards each edge: 2^-20 inside differs from the edge value by at most the
    // slope over 2^-20.
    for (uint32_t f = 0; f < a.faceCount(); f += 7) {
        const float e = std::ldexp(1.0f, -20), t = 0.3125f;
        const float pairs[3][4] = {{t, 0, t, e}, {0, t, e, t}, {t, 1 - t, t - e, 1 - t}};
        for (const auto& p : pairs) {
            const float onEdge = lt::sampleDisplacement(a, f, p[0], p[1]);
            const float inside = lt::sampleDisplacement(a, f, p[2], p[3]);
            EXPECT_LT(std::fabs(onEdge - inside), 1e-3f) << "face " << f;
        }
    }
}

TEST(DisplacementSampler, ClampsAndAbsentMap) {
    const Asset a = withMap(spot(), 4);
    EXPECT_EQ(bitsOf(lt::sampleDisplacement(a, 3, -0.5f, 0.25f)), bitsOf(lt::sampleDisplacement(a, 3, 0.0f, 0.25f)));
    EXPECT_EQ(bitsOf(lt::sampleDisplacement(a, 3, NAN, 0.25f)), bitsOf(lt::sampleDisplacement(a, 3, 0.0f, 0.25f)));
    EXPECT_EQ(bitsOf(lt::sampleDisplacement(a, 3, 0.5f, 2.0f)), bitsOf(lt::sampleDisplacement(a, 3, 0.5f, 1.0f)));
    EXPECT_EQ(bitsOf(lt::sampleDisplacement(a, 3, -0.0f, -0.0f)), bitsOf(decoded(a, a.faces[9])));
    EXPECT_EQ(lt::sampleDisplacement(spot(), 3, 0.25f, 0.25f), 0.0f);  // no map
    EXPECT_EQ(bitsOf(lt::kUnorm16), 0x37800080u);
    EXPECT_EQ(65535.0f * lt::kUnorm16, 1.0f);
}

// --- the baker -------------------------------------------------------------------------

// Every sample against the pattern itself: an interior sample is the pattern at its
// UV, a shared one the mean of the pattern at each face's UV for it (the seam
// weld). Bilinear reads of a 256-texel map of this pattern are within 1e-4 of it.
TEST(DisplacementBake, SamplesFollowThePatternAndWeldSeams) {
    const uint32_t R = 8;
    const Asset a = withMap(spot(), R);
    std::vector<double> sum(a.displacement.values.size(), 0.0);
    std::vector<uint32_t> count(sum.size(), 0);
    std::vector<double> first(sum.size(), -1.0);
    size_t seamSamples = 0;
    for (uint32_t f = 0; f < a.faceCount(); ++f) {
        const float* t = &a.faceUVs[6 * size_t(f)];
        for (uint32_t j = 0; j <= R; ++j)
            for (uint32_t i = 0; i + j <= R; ++i) {
                const double w1 = double(i) / R, w2 = double(j) / R, w0 = 1.0 - w1 - w2;
                const double p =
                    lt::test::displacementPattern(w0 * t[0] + w1 * t[2] + w2 * t[4], w0 * t[1] + w1 * t[3] + w2 * t[5]);
                const uint64_t k = lt::displacementSample(a, f, i, j);
                if (first[k] >= 0 && std::fabs(first[k] - p) > 1e-3 && count[k] == 1) ++seamSamples;
                if (first[k] < 0) first[k] = p;
                sum[k] += p;
                ++count[k];
            }
    }
    double worst = 0;
    for (size_t k = 0; k < sum.size(); ++k)
        if (count[k]) worst = std::max(worst, std::fabs(a.displacement.values[k] / 65535.0 - sum[k] / count[k]));
    EXPECT_LT(worst, 1.5e-4);
    EXPECT_GT(seamSamples, 100u) << "spot's UV seams should make shared samples read different texels";
}

TEST(DisplacementBake, DeterministicAndRoundTrips) {
    const Asset a = withMap(spot(), 0), b = withMap(spot(), 0);
    EXPECT_EQ(a.displacement.values, b.displacement.values);
    std::vector<uint8_t> bytesA, bytesB, bytesPlain;
    lt::TableBytes tb;
    ASSERT_TRUE(lt::writeAssetGlb(a, bytesA, &tb));
    ASSERT_TRUE(lt::writeAssetGlb(b, bytesB));
    EXPECT_EQ(bytesA, bytesB);
    EXPECT_EQ(tb.displacement, (a.displacement.faceEdges.size() + a.displacement.values.size()) * 2);  // u16 both
    Asset back;
    const lt::Status st = lt::readAssetGlb(bytesA.data(), bytesA.size(), "spot.glb", back);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(back.displacement.resolution, a.displacement.resolution);
    EXPECT_EQ(bitsOf(back.displacement.scale), bitsOf(0.375f));
    EXPECT_EQ(bitsOf(back.displacement.bias), bitsOf(-0.125f));
    EXPECT_EQ(back.displacement.faceEdges, a.displacement.faceEdges);
    EXPECT_EQ(back.displacement.values, a.displacement.values);
    // Without the map the file is what it was before maps existed.
    ASSERT_TRUE(lt::writeAssetGlb(spot(), bytesPlain));
    Asset cleared = back;
    cleared.displacement = lt::DisplacementMap{};
    std::vector<uint8_t> bytesCleared;
    ASSERT_TRUE(lt::writeAssetGlb(cleared, bytesCleared));
    EXPECT_EQ(bytesCleared, bytesPlain);
}

// The default resolution: the smallest power of two with R^2 / 2 samples per face
// for the map's mean texels per face.
TEST(DisplacementBake, DefaultResolutionCoversTheTexels) {
    const Asset& a = spot();
    double area = 0;
    for (uint32_t f = 0; f < a.faceCount(); ++f) {
        const float* t = &a.faceUVs[6 * size_t(f)];
        area += 0.5 * std::fabs((double(t[2]) - t[0]) * (double(t[5]) - t[1]) -
                                (double(t[3]) - t[1]) * (double(t[4]) - t[0]));
    }
    for (uint32_t size : {16u, 256u, 1024u, 4096u}) {
        const double perFace = area * size * size / a.faceCount();
        const uint32_t R = lt::chooseDisplacementResolution(a, patternImage(size));
        SCOPED_TRACE("map " + std::to_string(size) + ": " + std::to_string(perFace) + " texels per face, R " +
                     std::to_string(R));
        EXPECT_TRUE(R >= 1 && R <= 64 && (R & (R - 1)) == 0);
        if (R < 64) { EXPECT_GE(R * R / 2.0, perFace); }
        if (R > 1) { EXPECT_LT((R / 2) * (R / 2) / 2.0, perFace); }
    }
}

TEST(DisplacementBake, Errors) {
    Asset noUVs = bakeMesh(readObj(std::string(LOOPTESS_CORPUS_DIR) + "/meshes/fandisk.obj"), "fandisk.obj");
    lt::Status st = lt::bakeDisplacement(patternImage(8), lt::DisplacementSettings{}, noUVs, "fandisk.obj");
    EXPECT_EQ(st.code, lt::Status::BadInput);
    EXPECT_NE(st.message.find("fandisk.obj: a displacement map needs texture coordinates"), std::string::npos)
        << st.message;
    Asset a = spot();
    lt::DisplacementSettings ds;
    ds.resolution = 3;
    st = lt::bakeDisplacement(patternImage(8), ds, a, "spot.obj");
    EXPECT_EQ(st.code, lt::Status::Usage) << st.message;
    ds.resolution = 4;
    ds.scale = INFINITY;
    EXPECT_EQ(lt::bakeDisplacement(patternImage(8), ds, a, "spot.obj").code, lt::Status::Usage);
    ds.scale = 1;
    EXPECT_EQ(lt::bakeDisplacement(lt::GrayImage{}, ds, a, "spot.obj").code, lt::Status::BadInput);
}

}  // namespace
