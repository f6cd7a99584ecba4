// tests/check/test_loopcheck_bounds.cpp -- the bound loopcheck's hit-distance check gives a
// tested triangle from the reference surface over its (u, v) (SurfaceIndex in
// looptess/tools/check.h): against brute-force sampling on hand-made reference grids, and
// end to end on a CAD fillet whose coarse triangles have corner normals that agree
// while the surface bulges between them (fandisk baked with --crease-angle 40: the
// false "R2" failure this bound removes), where a wrong tessellation still fails; and
// N1's second look at a normal behind a coarse triangle, against the finer surface.
#include "check_internal.h"  // looptess_check_internal
#include "looptess/tools/file_io.h"
#include "tool_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using Height = std::function<double(double u, double v)>;

// A reference over base face 0: the (u, v) grid of step 1/n, every cell's lower and
// upper triangle (below u + v = 1), at (u, v, height(u, v)) with face normals (so
// every reference chord bound is ~0 and the bound is the deviation D alone).
//
//     v                 lower: (i, j) (i+1, j) (i, j+1)
//     ^ (i,j+1) (i+1,j+1) upper: (i+1, j) (i+1, j+1) (i, j+1)
//     |   +------+
//     |   | \ up |
//     |   |lo \  |
//     |   +------+
//     | (i,j)  (i+1,j)
//     +------------> u
lt::Tessellation grid(int n, const Height& height) {
    lt::Tessellation s;
    auto add = [&](int i0, int j0, int i1, int j1, int i2, int j2) {
        const int ij[3][2] = {{i0, j0}, {i1, j1}, {i2, j2}};
        float p[3][3];
        for (int k = 0; k < 3; ++k) {
            const double u = double(ij[k][0]) / n, v = double(ij[k][1]) / n;
            p[k][0] = float(u), p[k][1] = float(v), p[k][2] = float(height(u, v));
        }
        double e1[3], e2[3];
        for (int c = 0; c < 3; ++c) e1[c] = double(p[1][c]) - p[0][c], e2[c] = double(p[2][c]) - p[0][c];
        const double nr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                              e1[0] * e2[1] - e1[1] * e2[0]};
        const double len = std::sqrt(nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2]);
        for (int k = 0; k < 3; ++k) {
            for (int c = 0; c < 3; ++c) s.positions.push_back(p[k][c]), s.normals.push_back(float(nr[c] / len));
            s.face.push_back(0);
            s.uv.push_back(p[k][0]), s.uv.push_back(p[k][1]);
        }
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i + j < n; ++i) {
            add(i, j, i + 1, j, i, j + 1);
            if (i + j + 1 < n) add(i + 1, j, i + 1, j + 1, i, j + 1);
        }
    return s;
}

// One triangle of a tested tessellation: its corners' (u, v) on `face` (positions
// are made up: the bound must not read them).
lt::Tessellation tested(const double uv[6], uint32_t face = 0) {
    lt::Tessellation s;
    for (int k = 0; k < 3; ++k) {
        s.positions.insert(s.positions.end(), {float(k), 7.0f, -3.0f});
        s.normals.insert(s.normals.end(), {0.0f, 0.0f, 1.0f});
        s.face.push_back(face);
        s.uv.push_back(float(uv[2 * k])), s.uv.push_back(float(uv[2 * k + 1]));
    }
    return s;
}

lt::SurfaceIndex index(const lt::Tessellation& reference) {
    auto mesh = std::make_shared<lt::WeldedMesh>();
    lt::weldMesh(reference, *mesh);
    lt::SurfaceIndex out;
    out.build(reference, mesh);
    return out;
}

// The grid's piecewise-linear surface at (u, v), evaluated directly.
void onGrid(int n, const Height& height, double u, double v, double out[3]) {
    const int i = std::min(int(std::floor(u * n)), n - 1), j = std::min(int(std::floor(v * n)), n - 1);
    const double a = u * n - i, b = v * n - j;
    auto h = [&](int x, int y) { return double(float(height(double(x) / n, double(y) / n))); };
    out[0] = u, out[1] = v;
    out[2] = a + b <= 1 ? h(i, j) + a * (h(i + 1, j) - h(i, j)) + b * (h(i, j + 1) - h(i, j))
                        : h(i + 1, j + 1) + (1 - a) * (h(i, j + 1) - h(i + 1, j + 1)) +
                              (1 - b) * (h(i + 1, j) - h(i + 1, j + 1));
}

// The oracle: the reference's surface on the grid (onGrid), then its largest
// distance over the triangle `uv` from the plane through its values at the
// corners, sampled on a fine barycentric lattice.
double bruteForce(int n, const Height& height, const double uv[6]) {
    auto R = [&](double u, double v, double out[3]) { onGrid(n, height, u, v, out); };
    double at[3][3];
    for (int k = 0; k < 3; ++k) R(double(float(uv[2 * k])), double(float(uv[2 * k + 1])), at[k]);
    double worst = 0;
    const int m = 400;
    for (int x = 0; x <= m; ++x)
        for (int y = 0; x + y <= m; ++y) {
            const double b[3] = {double(m - x - y) / m, double(x) / m, double(y) / m};
            double u = 0, v = 0, p[3], d2 = 0;
            for (int k = 0; k < 3; ++k) u += b[k] * double(float(uv[2 * k])), v += b[k] * double(float(uv[2 * k + 1]));
            R(u, v, p);
            for (int c = 0; c < 3; ++c) {
                const double e = p[c] - (b[0] * at[0][c] + b[1] * at[1][c] + b[2] * at[2][c]);
                d2 += e * e;
            }
            worst = std::max(worst, std::sqrt(d2));
        }
    return worst;
}

const Height kBump = [](double u, double v) { return 2.7 * u * v * (1 - u - v); };  // 0 on the edges, 0.1 at the centre

TEST(LoopcheckBounds, ABumpBetweenFlatCornersIsSeen) {
    const lt::SurfaceIndex surface = index(grid(8, kBump));
    const double whole[6] = {0, 0, 1, 0, 0, 1};
    // Corner values 0: the deviation is the height, largest at the grid points nearest
    // the centre, (3/8, 3/8) and its turns: 2.7 * 3/8 * 3/8 * 2/8.
    EXPECT_NEAR(surface.bound(tested(whole), 0), 2.7 * 9.0 / 256.0, 1e-6);
    EXPECT_NEAR(surface.bound(tested(whole), 0), bruteForce(8, kBump, whole), 1e-6);
}

TEST(LoopcheckBounds, OffGridTrianglesMatchBruteForce) {
    for (const Height& h : {kBump, Height([](double u, double v) { return std::sin(9 * u) * std::cos(7 * v) / 4; })}) {
        const lt::SurfaceIndex surface = index(grid(16, h));
        const double triangles[][6] = {{0.1, 0.1, 0.7, 0.15, 0.2, 0.65},
                                       {0.33, 0.21, 0.31, 0.38, 0.52, 0.2},          // clockwise in (u, v)
                                       {0.0, 0.5, 0.5, 0.5, 0.0, 1.0},               // on the face's edges
                                       {0.401, 0.302, 0.405, 0.302, 0.401, 0.309}};  // inside one reference triangle
        for (const auto& uv : triangles) {
            SCOPED_TRACE(::testing::Message()
                         << uv[0] << "," << uv[1] << " " << uv[2] << "," << uv[3] << " " << uv[4] << "," << uv[5]);
            const double expected = bruteForce(16, h, uv), got = surface.bound(tested(uv), 0);
            EXPECT_GE(got, expected - 1e-6);         // never below what sampling finds
            EXPECT_LE(got, 1.01 * expected + 2e-6);  // and no looser than sampling's lattice
        }
    }
}

TEST(LoopcheckBounds, APlaneHasNoDeviation) {
    const lt::SurfaceIndex surface = index(grid(8, [](double u, double v) { return 0.3 * u - 0.2 * v + 0.1; }));
    const double uv[6] = {0.13, 0.21, 0.77, 0.05, 0.3, 0.6};
    EXPECT_LT(surface.bound(tested(uv), 0), 1e-6);
}

TEST(LoopcheckBounds, UnknownParametersGiveNoBound) {
    const lt::SurfaceIndex surface = index(grid(8, kBump));
    const double whole[6] = {0, 0, 1, 0, 0, 1}, outside[6] = {2, 2, 3, 2, 2, 3},
                 flat[6] = {0.1, 0.1, 0.2, 0.2, 0.3, 0.3};
    EXPECT_EQ(surface.bound(tested(whole, 1), 0), 0.0);  // a face the reference does not have
    EXPECT_EQ(surface.bound(tested(outside), 0), 0.0);
    EXPECT_EQ(surface.bound(tested(flat), 0), 0.0);  // no area in (u, v)
    lt::Tessellation mixed = tested(whole);
    mixed.face[1] = 1;
    EXPECT_EQ(surface.bound(mixed, 0), 0.0);
    lt::Tessellation nan = tested(whole);
    nan.uv[3] = NAN;
    EXPECT_EQ(surface.bound(nan, 0), 0.0);
}

// A hit's (face, u, v) from a triangle's barycentrics, and back to the triangle and
// its point there (loopcheck's fold rays compare hit points this way).
TEST(LoopcheckBounds, ParametersAndPointsRoundTrip) {
    const lt::Tessellation reference = grid(8, kBump);
    auto mesh = std::make_shared<lt::WeldedMesh>();
    lt::weldMesh(reference, *mesh);
    lt::SurfaceIndex surface;
    surface.build(reference, mesh);
    for (uint32_t t = 0; t < mesh->triangleCount(); t += 5) {
        uint32_t face = 9, back = 0;
        double uv[2], p[3], expected[3];
        ASSERT_TRUE(surface.parameters(t, 0.2, 0.3, face, uv));
        EXPECT_EQ(face, 0u);
        ASSERT_TRUE(surface.pointAt(face, uv, back, p));
        EXPECT_EQ(back, t);  // (u, v) inside triangle t
        onGrid(8, kBump, uv[0], uv[1], expected);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected[c], 1e-6);
    }
    uint32_t face = 0, back = 0;
    double uv[2] = {0.25, 0.25}, p[3];
    EXPECT_FALSE(surface.pointAt(1, uv, back, p));  // no such face
    EXPECT_FALSE(surface.parameters(uint32_t(mesh->triangleCount()), 0.2, 0.3, face, uv));
}

// --- end to end: fandisk's fillets at F = 1 ----------------------------------------------

fs::path workDir() {
    static const fs::path d = fs::temp_directory_path() / ("looptess_loopcheck_bounds_" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
}

// `loopbake INPUT -o DIR/NAME.glb OPTIONS...`, read back into `asset`.
void bake(const fs::path& input, const std::string& name, const std::vector<std::string>& options, lt::Asset& asset) {
    const fs::path glb = workDir() / (name + ".glb");
    std::vector<std::string> args = {input.string(), "-o", glb.string()};
    args.insert(args.end(), options.begin(), options.end());
    const lt::test::RunResult r = lt::test::runTool(LOOPBAKE_EXE, args, workDir());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::vector<uint8_t> bytes;
    lt::Status st = lt::readFile(glb.string(), bytes);
    if (st) st = lt::readAssetGlb(bytes.data(), bytes.size(), glb.string(), asset);
    ASSERT_TRUE(st) << st.message;
}

class LoopcheckFillet : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        bake(fs::path(LOOPTESS_CORPUS_DIR) / "meshes" / "fandisk.obj", "fandisk40", {"--crease-angle", "40"}, asset_);
    }
    static void TearDownTestSuite() { fs::remove_all(workDir()); }
    static lt::Asset asset_;
};
lt::Asset LoopcheckFillet::asset_;

TEST_F(LoopcheckFillet, CoarseTrianglesOverBulgesPassAndWrongOnesFail) {
    lt::CheckSettings settings;  // loopcheck's defaults: 100,000 rays, its seed
    lt::TessCase one;
    one.factor = 1.0f;
    settings.cases = {one};
    // `loopcheck ASSET --tess 1`'s checks of that tessellation, less the validator.
    lt::CheckContext ctx;
    ASSERT_TRUE(lt::prepareChecks(asset_, nullptr, settings, ctx));
    ASSERT_EQ(ctx.referenceFactor, 8.0f);
    lt::TessellationChecks checks;
    lt::Tessellation soup;
    ASSERT_TRUE(lt::checkEvaluation(ctx, lt::evalSettingsFor(asset_, one, settings), false, 1, checks, &soup));
    ASSERT_TRUE(checks.rays.distanceChecked);
    EXPECT_EQ(checks.rays.compared, 100000u);
    EXPECT_EQ(checks.rays.escaped, 0u);
    EXPECT_EQ(checks.rays.distanceFailures, 0u) << "worst " << checks.rays.maxToleranceRatio << "x the tolerance";

    // The same (face, u, v), every position 1% further from the centre: the bounds
    // read no position, so the wrong surface fails.
    double centre[3] = {0, 0, 0};
    for (size_t i = 0; i < soup.positions.size(); ++i) centre[i % 3] += soup.positions[i] / double(soup.vertexCount());
    for (size_t i = 0; i < soup.positions.size(); ++i)
        soup.positions[i] = float(centre[i % 3] + 1.01 * (soup.positions[i] - centre[i % 3]));
    ASSERT_TRUE(lt::checkTessellation(ctx, soup, false, 1, checks));
    EXPECT_GT(checks.rays.distanceFailures, checks.rays.compared / 2);
}

// --- N1 at F = 1: normals against the finer surface -------------------------------------

// OpenSubdiv's cube with three creases meeting at a corner (loop_cube_creases0): at
// F = 1 the corner's normal on a face is that face's own (spec, "Faces without a
// tangent plane"), 95 degrees from the flat triangle joining the face's three limit
// points, while the finer surface at the corner agrees with it. Before N1 judged
// again against the finer surface, loopcheck failed this right asset. The same cube
// open (one face's two triangles removed: no ray reference, so loopcheck builds a
// finer surface for the normals alone) likewise. Every normal flipped still fails.
TEST(LoopcheckCoarseNormals, AreJudgedAgainstTheFinerSurface) {
    const fs::path cube = fs::path(LOOPTESS_CORPUS_DIR) / "opensubdiv-loop" / "loop_cube_creases0.obj";
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(lt::readFile(cube.string(), bytes));
    const std::string text(bytes.begin(), bytes.end());
    const fs::path open = workDir() / "cube_open.obj";
    {
        std::ofstream out(open);
        for (size_t at = 0; at < text.size();) {
            const size_t end = std::min(text.find('\n', at), text.size());
            const std::string line = text.substr(at, end - at);
            if (line.rfind("f 5/5/13 ", 0) != 0 && line.rfind("f 7/7/16 ", 0) != 0) out << line << '\n';
            at = end + 1;
        }
    }
    for (const fs::path& input : {cube, open}) {
        SCOPED_TRACE(input.filename().string());
        lt::Asset asset;
        bake(input, input.stem().string(), {}, asset);
        lt::CheckSettings settings;
        settings.rays = 1000;
        lt::TessCase one;
        one.factor = 1.0f;
        settings.cases = {one};
        lt::CheckContext ctx;
        ASSERT_TRUE(lt::prepareChecks(asset, nullptr, settings, ctx));
        lt::TessellationChecks checks;
        lt::Tessellation soup;
        ASSERT_TRUE(lt::checkEvaluation(ctx, lt::evalSettingsFor(asset, one, settings), false, 1, checks, &soup));
        EXPECT_EQ(checks.normals.against, 0u) << checks.normals.firstFailure;
        EXPECT_GE(checks.normals.refined, 1u);

        for (float& n : soup.normals) n = -n;
        ASSERT_TRUE(lt::checkTessellation(ctx, soup, false, 1, checks));
        EXPECT_GT(checks.normals.against, checks.normals.judged / 2);
        EXPECT_EQ(checks.normals.refined, 0u);
    }
    fs::remove_all(workDir());
}

}  // namespace
