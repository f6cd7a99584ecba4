// The README's hierarchical-edit example: a raised ridge on
// spot's back, tests/data/spot-ridge-edits.json (scripts/make_ridge_edits.py: one
// level-3 `add` edit along the normal per level-3 vertex on the spine region).
//
// 1. The real loopbake bakes it, and loopcheck passes the asset with --source and
//    --edits at its default factors (structure, accuracy against OpenSubdiv with
//    the edits, weld, rays, the glTF-Validator).
// 2. The ridge is there: at F = 8 (runtime depth 3, the edits' level) the CPU
//    evaluation of the edited bake departs from the plain bake's, at the same
//    (base face, u, v), by at least half the largest edit somewhere; on base faces
//    more than 3 vertex rings from every edited face it is the plain bake's, bit
//    for bit, in emission order.
// 3. `looprender --cpu --edit-scale 0` captures the plain surface (within 1e-6 of
//    the diagonal at each (face, u, v)): edits with value 0 change nothing.
#include "input_edit.h"
#include "looptess/tools/baker.h"
#include "looptess/tools/file_io.h"
#include "looptess/runtime.h"
#include "sanitizer.h"
#include "tool_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>
#include <unistd.h>

namespace fs = std::filesystem;

namespace lt::test {
namespace {

const std::string kSpot = std::string(LOOPTESS_TEST_DATA) + "/spot.obj";
const std::string kEdits = std::string(LOOPTESS_TEST_DATA) + "/spot-ridge-edits.json";

fs::path workDir() {
    static const fs::path d = [] {
        fs::path p = fs::temp_directory_path() / ("looptess_edits_example_" + std::to_string(getpid()));
        fs::create_directories(p);
        return p;
    }();
    return d;
}

// Bakes spot with and without the ridge once, through the real loopbake.
class EditsExample : public ::testing::Test {
protected:
    static fs::path plainGlb() { return workDir() / "spot.glb"; }
    static fs::path ridgeGlb() { return workDir() / "spot-ridge.glb"; }

    static void SetUpTestSuite() {
        RunResult plain = runTool(LOOPBAKE_EXE, {kSpot, "-o", plainGlb().string()}, workDir());
        RunResult ridge = runTool(LOOPBAKE_EXE, {kSpot, "--edits", kEdits, "-o", ridgeGlb().string(), "-v"}, workDir());
        bakeErrors = plain.err + ridge.err;
        baked = plain.exitCode == 0 && ridge.exitCode == 0;
        if (baked) std::printf("[ figures  ] loopbake -v:\n%s", ridge.err.c_str());
    }
    static void TearDownTestSuite() { fs::remove_all(workDir()); }

    void SetUp() override { ASSERT_TRUE(baked) << bakeErrors; }

    static Asset load(const fs::path& path) {
        std::vector<uint8_t> bytes;
        Asset asset;
        Status st = readFile(path.string(), bytes);
        if (st) st = readAssetGlb(bytes.data(), bytes.size(), path.string(), asset);
        EXPECT_TRUE(st) << st.message;
        return asset;
    }

    static inline bool baked = false;
    static inline std::string bakeErrors;
};

double diagonal(const Asset& asset) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < asset.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], asset.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], asset.positions[i]);
    }
    return std::hypot(double(hi[0]) - lo[0], double(hi[1]) - lo[1], double(hi[2]) - lo[2]);
}

double distance(const float* a, const float* b) {
    return std::hypot(double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]);
}

// A captured vertex's place: base face and (u, v), by their bits. At a power-of-two
// factor with equal spacing every patch level emits points of one dyadic lattice,
// so two bakes of one mesh emit the same places whatever their patch classes.
using Place = std::tuple<uint32_t, uint32_t, uint32_t>;
Place place(uint32_t face, float u, float v) {
    uint32_t bu, bv;
    std::memcpy(&bu, &u, 4);
    std::memcpy(&bv, &v, 4);
    return {face, bu, bv};
}

// Position per place of a soup (an unwelded soup repeats places; the first wins).
std::map<Place, const float*> byPlace(const Tessellation& t) {
    std::map<Place, const float*> out;
    for (size_t i = 0; i < t.vertexCount(); ++i)
        out.emplace(place(t.face[i], t.uv[2 * i], t.uv[2 * i + 1]), &t.positions[3 * i]);
    return out;
}

// The largest distance between the soups at shared places, and how many they share.
std::pair<double, size_t> largestDeparture(const Tessellation& a, const std::map<Place, const float*>& b) {
    double worst = 0;
    size_t shared = 0;
    for (size_t i = 0; i < a.vertexCount(); ++i) {
        auto it = b.find(place(a.face[i], a.uv[2 * i], a.uv[2 * i + 1]));
        if (it == b.end()) continue;
        worst = std::max(worst, distance(&a.positions[3 * i], it->second));
        ++shared;
    }
    return {worst, shared};
}

TEST_F(EditsExample, PassesLoopcheck) {
    // loopcheck's default factors: F = 1 and 3.3 draw at depths 0 and 2, without the
    // level-3 edits (their accuracy reference holds only the edits they show, and
    // their ray distances are not compared with the F = 16 reference, which shows
    // the ridge); F = 5, 8 and screen=8 draw at depth 3, with the ridge.
    // Under ASan one factor of each kind and no rays: their references (one per depth
    // that shows fewer edits, 2.8 M triangles each) took 125-163 s there; the ray code
    // runs under ASan in LoopcheckCorpus and RealMeshes.
    std::vector<std::string> args = {ridgeGlb().string(),  "--source", kSpot, "--edits", kEdits, "--rays",
                                     kAsan ? "0" : "20000"};
    if (kAsan) args.insert(args.end(), {"--tess", "3.3", "8"});
    RunResult all = runTool(LOOPCHECK_EXE, args, workDir());
    EXPECT_EQ(all.exitCode, 0) << all.out << all.err;
    EXPECT_NE(all.out.find("4293 hierarchical edits down to level 3"), std::string::npos) << all.out;
    // Without --edits the source is the plain spot: the control meshes differ (M1).
    RunResult without =
        runTool(LOOPCHECK_EXE, {ridgeGlb().string(), "--source", kSpot, "--rays", "0", "--tess", "1", "-q"}, workDir());
    EXPECT_EQ(without.exitCode, 3) << without.out << without.err;
    std::printf("[ figures  ] loopcheck: %s", all.out.substr(all.out.rfind('\n', all.out.size() - 2) + 1).c_str());
}

TEST_F(EditsExample, TheRidgeIsThereAndNowhereElse) {
    const Asset plain = load(plainGlb()), ridge = load(ridgeGlb());
    InputMesh edits;  // the edits alone, for where and how large they are
    std::vector<uint8_t> json;
    ASSERT_TRUE(readFile(kEdits, json));
    ASSERT_TRUE(
        parseEditsJson(std::string_view(reinterpret_cast<const char*>(json.data()), json.size()), kEdits, edits));
    ASSERT_EQ(ridge.editCount(), edits.edits.size());
    float largest = 0;
    for (const auto& e : edits.edits)
        largest = std::max(largest, float(std::hypot(e.value[0], e.value[1], e.value[2])));

    // Base faces within 3 vertex rings of the edited faces (spot's control mesh).
    const std::set<uint32_t> near = facesNearEdits(edits.edits, plain.faces, 3);

    EvalSettings settings;
    settings.tessFactor = 8;
    ASSERT_EQ(runtimeDepth(ridge, 8), 3u);
    Tessellation a, b;
    evaluateCpu(ridge, ridge.positions.data(), settings, a);
    evaluateCpu(plain, plain.positions.data(), settings, b);
    const double diag = diagonal(plain);
    const auto [departure, shared] = largestDeparture(a, byPlace(b));
    EXPECT_GT(shared, a.vertexCount() / 2);
    EXPECT_GE(departure, 0.5 * largest);

    const std::vector<float> fa = verticesOutside(a, near), fb = verticesOutside(b, near);
    EXPECT_GT(plain.faceCount() - near.size(), plain.faceCount() / 2);
    ASSERT_EQ(fa.size(), fb.size());
    EXPECT_EQ(std::memcmp(fa.data(), fb.data(), fa.size() * sizeof(float)), 0);
    std::printf(
        "[ figures  ] %u edits, largest %.4f (%.2f%% of the diagonal); F=8: the ridge rises %.4f (%.2f%%); "
        "%zu faces within 3 rings, %zu far vertices bit for bit\n",
        ridge.editCount(), largest, 100 * largest / diag, departure, 100 * departure / diag, near.size(),
        fa.size() / 6);
}

// Reads looprender's binary PLY capture (looprender_common.h's writePly: x y z nx ny nz face u v,
// then s t and tx ty tz tw when the asset has UVs).
bool readCapture(const fs::path& path, Tessellation& t) {
    const std::string text = readText(path);
    const std::string end = "end_header\n", count = "element vertex ";
    const size_t body = text.find(end), at = text.find(count);
    if (body == std::string::npos || at == std::string::npos) return false;
    const size_t n = std::stoul(text.substr(at + count.size()));
    const std::string header = text.substr(0, body);
    const size_t stride = 36 + (header.find("property float s\n") != std::string::npos ? 8 : 0) +
                          (header.find("property float tx\n") != std::string::npos ? 16 : 0);
    if (text.size() < body + end.size() + stride * n) return false;
    const char* p = text.data() + body + end.size();
    t = {};
    for (size_t i = 0; i < n; ++i, p += stride) {
        float f[9];
        std::memcpy(f, p, 36);
        int32_t face;
        std::memcpy(&face, p + 24, 4);
        t.positions.insert(t.positions.end(), f, f + 3);
        t.normals.insert(t.normals.end(), f + 3, f + 6);
        t.face.push_back(uint32_t(face));
        t.uv.insert(t.uv.end(), f + 7, f + 9);
    }
    return true;
}

TEST_F(EditsExample, EditScaleZeroDrawsThePlainSurface) {
    for (const char* factor : asanSample<const char*>({"4", "8"}, 2)) {  // ASan: F = 4
        SCOPED_TRACE(std::string("F=") + factor);
        const fs::path zero = workDir() / "zero.ply", plainPly = workDir() / "plain.ply";
        RunResult r0 =
            runTool(LOOPRENDER_EXE,
                    {"--cpu", ridgeGlb().string(), "--tess", factor, "--edit-scale", "0", "--capture", zero.string()},
                    workDir());
        RunResult r1 =
            runTool(LOOPRENDER_EXE, {"--cpu", plainGlb().string(), "--tess", factor, "--capture", plainPly.string()},
                    workDir());
        ASSERT_EQ(r0.exitCode, 0) << r0.err;
        ASSERT_EQ(r1.exitCode, 0) << r1.err;
        Tessellation a, b;
        ASSERT_TRUE(readCapture(zero, a));
        ASSERT_TRUE(readCapture(plainPly, b));
        const double diag = diagonal(load(plainGlb()));
        const auto [departure, shared] = largestDeparture(a, byPlace(b));
        EXPECT_GT(shared, a.vertexCount() / 2);
        EXPECT_LE(departure, 1e-6 * diag);
        std::printf(
            "[ figures  ] --edit-scale 0, F=%s: %zu of %zu captured vertices at plain places, within %.2e of the "
            "diagonal\n",
            factor, shared, a.vertexCount(), departure / diag);
    }
}

}  // namespace
}  // namespace lt::test
