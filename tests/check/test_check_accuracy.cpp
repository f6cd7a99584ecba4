// tests/check/test_check_accuracy.cpp -- loopcheck's accuracy check (checkAccuracy): its
// allowances for float resolution (check.h) pass the runtime's normal on a sliver
// and its positions far from the origin, within float rounding, and nothing more.
//
// jaco_finger_distal with creases above 40 degrees: face 550 is a sliver (the smaller
// singular value of its [dP/du dP/dv] is 8.1e-7 against 1.7e-4 for the larger). Its
// point (u, v) = (0, 0.875), born at level 3, is drawn at F = 5 (depth 3) with a
// normal 5.7e-3 radians (1 - cos 1.6e-5) from OpenSubdiv's in double: computed
// exactly in double from the same tables, the level-3 points' float rounding
// (1e-9 .. 3e-9) turns it that much. Beside it, face 0 is well shaped.
#include "osd_reference.h"
#include "sanitizer.h"

#include "check_internal.h"  // looptess_check_internal
#include "looptess/runtime.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

namespace lt {
namespace {

// The soup's vertices at (face, u, v), in soup order.
std::vector<size_t> verticesAt(const Tessellation& soup, uint32_t face, float u, float v) {
    std::vector<size_t> found;
    for (size_t i = 0; i < soup.vertexCount(); ++i)
        if (soup.face[i] == face && soup.uv[2 * i] == u && soup.uv[2 * i + 1] == v) found.push_back(i);
    return found;
}

// A soup of the listed vertices of `soup`, one sample each.
Tessellation pick(const Tessellation& soup, const std::vector<size_t>& at) {
    Tessellation out;
    for (size_t i : at) {
        out.positions.insert(out.positions.end(), &soup.positions[3 * i], &soup.positions[3 * i + 3]);
        out.normals.insert(out.normals.end(), &soup.normals[3 * i], &soup.normals[3 * i + 3]);
        out.face.push_back(soup.face[i]);
        out.uv.insert(out.uv.end(), &soup.uv[2 * i], &soup.uv[2 * i + 2]);
    }
    return out;
}

// Turns normal i about an axis orthogonal to it by `angle` radians.
void turn(Tessellation& soup, size_t i, double angle) {
    float* n = &soup.normals[3 * i];
    const double axis[3] = {n[1], -n[0], 0};  // orthogonal to n (n is not along z here)
    const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1]);
    double cross[3] = {axis[1] / len * n[2], -axis[0] / len * n[2], (axis[0] * n[1] - axis[1] * n[0]) / len};
    for (int k = 0; k < 3; ++k) n[k] = float(std::cos(angle) * n[k] + std::sin(angle) * cross[k]);
}

TEST(CheckAccuracy, FloatResolutionWidensOnlyThinFaces) {
    // Arithmetic on one mesh's oracle (18 s in the release build, a large multiple
    // under ASan); the sanitizer run covers checkAccuracy through loopcheck's tests.
    if (test::kAsan) GTEST_SKIP() << "release build only";
    SourceOracle oracle;
    oracle.mesh = test::loadObj(std::string(LOOPTESS_TEST_DATA) + "/real/jaco_finger_distal.obj");
    addCreasesByAngle(oracle.mesh, 40);
    ASSERT_TRUE(oracle.build());
    Asset asset;
    ASSERT_TRUE(bake(oracle.mesh, BakeSettings{}, asset));
    oracle.assetDepth = asset.maxDepth();
    EvalSettings eval;
    eval.tessFactor = 5;
    ASSERT_EQ(runtimeDepth(asset, eval.tessFactor), 3u);
    Tessellation full;
    evaluateCpu(asset, asset.positions.data(), eval, full);
    const std::vector<size_t> sliver = verticesAt(full, 550, 0.0f, 0.875f);
    std::vector<size_t> wide;
    for (size_t i = 0; i < full.vertexCount() && wide.empty(); ++i)
        if (full.face[i] == 0 && full.uv[2 * i] > 0 && full.uv[2 * i + 1] > 0 &&
            full.uv[2 * i] + full.uv[2 * i + 1] < 1)
            wide.push_back(i);  // inside face 0
    ASSERT_FALSE(sliver.empty());
    ASSERT_FALSE(wide.empty());
    const double diagonal = test::bboxDiagonal(oracle.mesh);

    auto check = [&](const Tessellation& soup) {
        CheckSettings settings;
        settings.accuracySamples = soup.vertexCount();  // one stratum per vertex
        AccuracyResult r;
        checkAccuracy(oracle, soup, 3, diagonal, settings, 1, r);
        EXPECT_EQ(r.sampled, soup.vertexCount());
        EXPECT_EQ(r.positionFailures, 0u) << r.firstFailure;
        return r;
    };
    // As drawn: past 1e-5 on the sliver, within float resolution.
    Tessellation soup = pick(full, {sliver[0], wide[0]});
    AccuracyResult drawn = check(soup);
    EXPECT_EQ(drawn.normalFailures, 0u) << drawn.firstFailure;
    EXPECT_EQ(drawn.floatLimited, 1u);

    // The sliver's normal turned by 0.12 radians more (past its 0.052), or flipped;
    // the wide face's by 0.01 (1 - cos 5e-5): each fails.
    for (double angle : {0.12, 3.14159}) {
        Tessellation bad = soup;
        turn(bad, 0, angle);
        EXPECT_EQ(check(bad).normalFailures, 1u) << angle;
    }
    Tessellation bad = soup;
    turn(bad, 1, 0.01);
    AccuracyResult wideResult = check(bad);
    EXPECT_EQ(wideResult.normalFailures, 1u);
    EXPECT_EQ(wideResult.floatLimited, 1u);  // the sliver's, as drawn
}

// A model placed far from the origin, as a scene in world coordinates: spot moved
// 300 diagonals out along (1, -1, 0.5). Its float points are about eps |P| apart
// (2.5e-5 of the diagonal there), and the runtime's positions, float sums level
// after level, are off OpenSubdiv's by up to 3.7e-5 of the diagonal: A1 failed every
// such right asset. The allowance (2 + depth) eps |P| (check.h) passes them; a
// point moved by 1e-3 of the diagonal still fails.
TEST(CheckAccuracy, FloatResolutionOfPositionsFarFromTheOrigin) {
    SourceOracle oracle;
    oracle.mesh = test::loadObj(test::corpusMesh("spot.obj"));
    const double diagonal = test::bboxDiagonal(oracle.mesh);
    const double offset[3] = {300 * diagonal, -300 * diagonal, 150 * diagonal};
    for (size_t i = 0; i < oracle.mesh.positions.size(); ++i)
        oracle.mesh.positions[i] = float(oracle.mesh.positions[i] + offset[i % 3]);
    ASSERT_TRUE(oracle.build());
    Asset asset;
    ASSERT_TRUE(bake(oracle.mesh, BakeSettings{}, asset));
    oracle.assetDepth = asset.maxDepth();
    EvalSettings eval;
    eval.tessFactor = 8;
    const uint32_t depth = runtimeDepth(asset, eval.tessFactor);
    Tessellation soup;
    evaluateCpu(asset, asset.positions.data(), eval, soup);
    CheckSettings settings;
    settings.accuracySamples = 3000;
    AccuracyResult r;
    checkAccuracy(oracle, soup, depth, diagonal, settings, 1, r);
    EXPECT_EQ(r.positionFailures, 0u) << r.firstFailure;
    EXPECT_EQ(r.normalFailures, 0u) << r.firstFailure;
    EXPECT_GT(r.floatLimited, 0u);  // the allowance was needed
    Tessellation moved = pick(soup, {0, soup.vertexCount() / 2});
    moved.positions[0] += float(1e-3 * diagonal);
    settings.accuracySamples = 2;
    checkAccuracy(oracle, moved, depth, diagonal, settings, 1, r);
    EXPECT_EQ(r.positionFailures, 1u);
}

// A1 judges every base corner: a single wrong vertex at a base
// face's corner (u, v) in {(0, 0), (1, 0), (0, 1)} -- where degenerate-corner defects
// live -- fails A1 however few vertices the stratified sample takes. Spot at F = 8
// emits far more vertices than the 1000 sampled here; the planted corner vertex is
// one the sample leaves out (a probe with a wrong interior vertex in its place finds
// nothing), and A1 still fails on it, by name.
TEST(CheckAccuracy, EveryBaseCornerIsJudged) {
    SourceOracle oracle;
    oracle.mesh = test::loadObj(test::corpusMesh("spot.obj"));
    ASSERT_TRUE(oracle.build());
    Asset asset;
    ASSERT_TRUE(bake(oracle.mesh, BakeSettings{}, asset));
    oracle.assetDepth = asset.maxDepth();
    EvalSettings eval;
    eval.tessFactor = 8;
    const uint32_t depth = runtimeDepth(asset, eval.tessFactor);
    Tessellation soup;
    evaluateCpu(asset, asset.positions.data(), eval, soup);
    const double diagonal = test::bboxDiagonal(oracle.mesh);
    CheckSettings settings;
    settings.accuracySamples = 1000;
    ASSERT_GT(soup.vertexCount(), 100 * settings.accuracySamples);
    uint64_t cornerCount = 0;
    size_t interior = SIZE_MAX;
    for (size_t i = 0; i < soup.vertexCount(); ++i) {
        cornerCount += baseCorner(soup.uv[2 * i], soup.uv[2 * i + 1]) >= 0;
        if (interior == SIZE_MAX && soup.uv[2 * i] > 0 && soup.uv[2 * i + 1] > 0 &&
            soup.uv[2 * i] + soup.uv[2 * i + 1] < 1)
            interior = i;
    }
    ASSERT_NE(interior, SIZE_MAX);
    AccuracyResult r;
    checkAccuracy(oracle, soup, depth, diagonal, settings, 1, r);
    ASSERT_EQ(r.positionFailures + r.normalFailures + r.noLimit, 0u) << r.firstFailure;

    // Vertex i moved off the surface by 1e-3 of the diagonal and its normal turned over.
    auto plant = [&](Tessellation& s, size_t i) {
        s.positions[3 * i] += float(1e-3 * diagonal);
        for (int k = 0; k < 3; ++k) s.normals[3 * i + size_t(k)] = -s.normals[3 * i + size_t(k)];
    };
    // The first base-corner vertex whose index the stratified sample passes over: with
    // a wrong interior vertex at that index instead, A1 finds nothing (the sample
    // depends on the vertex count and the seed alone).
    size_t corner = SIZE_MAX;
    for (size_t i = 0; i < soup.vertexCount() && corner == SIZE_MAX; ++i) {
        if (baseCorner(soup.uv[2 * i], soup.uv[2 * i + 1]) < 0) continue;
        Tessellation probe = soup;
        for (int k = 0; k < 3; ++k) probe.positions[3 * i + size_t(k)] = soup.positions[3 * interior + size_t(k)];
        for (int k = 0; k < 3; ++k) probe.normals[3 * i + size_t(k)] = soup.normals[3 * interior + size_t(k)];
        probe.face[i] = soup.face[interior];
        probe.uv[2 * i] = soup.uv[2 * interior];
        probe.uv[2 * i + 1] = soup.uv[2 * interior + 1];
        plant(probe, i);
        checkAccuracy(oracle, probe, depth, diagonal, settings, 1, r);
        if (r.positionFailures + r.normalFailures == 0) corner = i;
    }
    ASSERT_NE(corner, SIZE_MAX);

    Tessellation bad = soup;
    plant(bad, corner);
    checkAccuracy(oracle, bad, depth, diagonal, settings, 1, r);
    EXPECT_EQ(r.positionFailures, 1u) << r.firstFailure;
    EXPECT_EQ(r.normalFailures, 1u) << r.firstFailure;
    std::ostringstream where;
    where << "vertex " << corner << " face " << bad.face[corner] << " (u, v) = (" << bad.uv[2 * corner] << ", "
          << bad.uv[2 * corner + 1] << ")";
    EXPECT_NE(r.firstFailure.find(where.str()), std::string::npos) << r.firstFailure;
    EXPECT_EQ(r.corners, cornerCount);  // every one, not a sample
    EXPECT_GE(r.sampled, settings.accuracySamples);
    EXPECT_LE(r.sampled, settings.accuracySamples + cornerCount);
}

// N1 without --source (check_internal.h, cageOracle): on winding_pinch at F = 16 two
// normals stand behind their triangles at vertices whose 1-ring winds twice round them
// (tests/data/normals/winding_pinch.obj). OpenSubdiv's limit of the asset's own
// control mesh confirms them there, smooth vertices; turned over, every normal at
// those points is refused.
TEST(CheckNormals, TheAssetsOwnControlMeshConfirmsSmoothCorners) {
    const InputMesh mesh = test::loadObj(std::string(LOOPTESS_TEST_DATA) + "/normals/winding_pinch.obj");
    Asset asset;
    ASSERT_TRUE(bake(mesh, BakeSettings{}, asset));
    EvalSettings eval;
    eval.tessFactor = 16;
    const uint32_t depth = runtimeDepth(asset, eval.tessFactor);
    Tessellation soup;
    evaluateCpu(asset, asset.positions.data(), eval, soup);
    SourceOracle cage;
    std::vector<char> smooth;
    ASSERT_TRUE(cageOracle(asset, cage, smooth));
    auto confirm = [&](const Tessellation& s) {
        return [&](size_t v) {
            const int corner = baseCorner(s.uv[2 * v], s.uv[2 * v + 1]);
            return corner >= 0 && smooth[asset.faces[3 * size_t(s.face[v]) + size_t(corner)]] &&
                   normalConfirmed(cage, s, v, depth, CheckSettings{});
        };
    };
    NormalResult n;
    checkNormals(soup, n);
    ASSERT_EQ(n.against, 2u) << "the triangles alone";
    std::vector<size_t> behind;  // the two, as checkNormals asks about them
    checkNormals(soup, n, nullptr, [&](size_t v) {
        behind.push_back(v);
        return false;
    });
    ASSERT_EQ(behind.size(), 2u);
    checkNormals(soup, n, nullptr, confirm(soup));
    EXPECT_EQ(n.against, 0u) << n.firstFailure;
    EXPECT_EQ(n.confirmed, 2u);
    Tessellation turned = soup;  // every normal at those two points turned over
    for (size_t i = 0; i < turned.vertexCount(); ++i)
        for (size_t v : behind)
            if (std::memcmp(&turned.positions[3 * i], &soup.positions[3 * v], 12) == 0)
                for (int k = 0; k < 3; ++k) turned.normals[3 * i + size_t(k)] = -soup.normals[3 * i + size_t(k)];
    checkNormals(turned, n, nullptr, confirm(turned));
    EXPECT_GE(n.against, 9u) << "refused";  // the rest now face their own triangles
    EXPECT_EQ(n.confirmed, 0u);
}

}  // namespace
}  // namespace lt
