// tests/vulkan/test_images.cpp -- golden image tests of the Vulkan path: spot and the Duck,
// baked in-process, rendered offscreen from
// looprender's default camera (shaded, coloured by level, and by the TEXCOORD_0 the
// GPU draw emits); and whole scenes baked by loopbake and drawn by looprender
// --color material (the textured Duck, the skinned Fox at two times of its walk,
// RobotExpressive waving: 14 meshes, 19 primitives, skin and morph weights;
// OrientationTest's 13 meshes, BoxTextured). Compared with the PNGs in
// tests/data/golden/images/ at a tolerance (tests/data/golden/README.md).
//
// lavapipe renders deterministically, so on one driver the images match exactly;
// the tolerance only absorbs rasterization changes of driver updates (a pixel may
// move along a silhouette), never a changed surface or shading.
//
// On a mismatch the test writes NAME.actual.png and NAME.diff.png (differing
// pixels red over the golden image, dimmed) to LOOPTESS_IMAGE_OUTPUT and names
// them. LOOPTESS_UPDATE_GOLDEN=1 rewrites the golden images instead of comparing.
#include "test_vulkan_support.h"

#include "looprender_common.h"  // cameraMatrix, writePngFile (apps/looprender)

#include "looptess/tools/file_io.h"
#include "tool_run.h"

#include <stb_image.h>

#include <cstdlib>
#include <filesystem>

namespace lt::test {
namespace {

namespace fs = std::filesystem;

// A pixel differs when a channel differs by more than kChannelTolerance; an image
// fails when more than kMaxDifferingFraction of its pixels differ.
constexpr int kChannelTolerance = 16;
constexpr double kMaxDifferingFraction = 0.005;
constexpr uint32_t kSize = 256;

struct Case {
    const char* name;  // golden file stem
    std::string path;  // control mesh
    float factor;
    Coloring coloring;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::string spotPath() { return std::string(LOOPTESS_TEST_DATA) + "/spot.obj"; }

// Decoded RGBA8 pixels of a PNG file; empty when it cannot be read.
Image readPng(const fs::path& path) {
    std::vector<uint8_t> bytes;
    Image image;
    if (!readFile(path.string(), bytes)) return image;
    int w = 0, h = 0, channels = 0;
    stbi_uc* pixels = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 4);
    if (!pixels) return image;
    image.width = uint32_t(w);
    image.height = uint32_t(h);
    image.rgba.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
    stbi_image_free(pixels);
    return image;
}

// Pixels of `a` and `b` (same size) that differ by more than the tolerance, and a
// diff image showing them.
size_t compareImages(const Image& a, const Image& b, Image& diff) {
    diff = a;
    size_t differing = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
        bool differs = worst > kChannelTolerance;
        differing += differs ? 1 : 0;
        for (int c = 0; c < 3; ++c) diff.rgba[i + c] = differs ? (c == 0 ? 255 : 0) : uint8_t(128 + b.rgba[i + c] / 2);
        diff.rgba[i + 3] = 255;
    }
    return differing;
}

void writePng(const fs::path& path, const Image& image) {
    Status st = looprender::writePngFile(path.string(), image.width, image.height, image.rgba);
    EXPECT_TRUE(st) << st.message;
}

// Compares `actual` with golden image NAME.png (or rewrites it with
// LOOPTESS_UPDATE_GOLDEN=1); on a mismatch writes NAME.actual.png and NAME.diff.png.
void checkGolden(const std::string& name, const Image& actual) {
    const fs::path golden = fs::path(LOOPTESS_TEST_DATA) / "golden" / "images" / (name + ".png");
    if (const char* update = std::getenv("LOOPTESS_UPDATE_GOLDEN"); update && std::string(update) == "1") {
        fs::create_directories(golden.parent_path());
        writePng(golden, actual);
        std::printf("LOOPTESS_UPDATE_GOLDEN=1: rewrote %s\n", golden.string().c_str());
        return;
    }
    Image expected = readPng(golden);
    ASSERT_FALSE(expected.rgba.empty()) << golden << " is missing or unreadable; (re)generate it with\n"
                                        << "  LOOPTESS_UPDATE_GOLDEN=1 build/tests/test_images\n"
                                        << "and commit it (see tests/data/golden/README.md)";
    ASSERT_EQ(expected.width, actual.width);
    ASSERT_EQ(expected.height, actual.height);
    Image diff;
    size_t differing = compareImages(actual, expected, diff);
    size_t allowed = size_t(kMaxDifferingFraction * double(kSize) * kSize);
    std::printf("[ figures  ] %s: %zu of %u pixels differ by more than %d (allowed %zu)\n", name.c_str(), differing,
                kSize * kSize, kChannelTolerance, allowed);
    const fs::path out = LOOPTESS_IMAGE_OUTPUT;
    std::error_code ignored;  // a previous run's failure images are stale now
    fs::remove(out / (name + ".actual.png"), ignored);
    fs::remove(out / (name + ".diff.png"), ignored);
    if (differing <= allowed) return;
    fs::create_directories(out);
    writePng(out / (name + ".actual.png"), actual);
    writePng(out / (name + ".diff.png"), diff);
    ADD_FAILURE() << name << ": " << differing << " pixels differ from " << golden.string() << " (allowed " << allowed
                  << "); wrote " << (out / name).string() << ".actual.png and .diff.png (differing pixels red). "
                  << "If the change is intended, see tests/data/golden/README.md";
}

// A kSize x kSize image of `frame` from looprender's default framing (as the README
// pictures).
RenderSettings defaultView(const Asset& asset, const FrameSettings& frame) {
    looprender::Options view;
    view.width = view.height = kSize;
    RenderSettings rs;
    rs.width = rs.height = kSize;
    rs.frame = frame;
    looprender::cameraMatrix(view, asset, rs.frame.mvp, rs.frame.light);
    return rs;
}

class GoldenImages : public VulkanTest, public ::testing::WithParamInterface<Case> {};

TEST_P(GoldenImages, MatchWithinTolerance) {
    const Case& c = GetParam();
    int depth = int(std::ceil(std::log2(c.factor)));
    const Baked* b = baked(c.path, depth);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    FrameSettings frame;
    frame.tessFactor = c.factor;
    frame.coloring = c.coloring;
    const RenderSettings rs = defaultView(b->asset, frame);
    Image actual;
    Status st = renderImage(*surface, rs, actual);
    ASSERT_TRUE(st) << st.message;

    checkGolden(c.name, actual);
}

INSTANTIATE_TEST_SUITE_P(SpotAndDuck, GoldenImages,
                         ::testing::Values(Case{"spot-shaded", spotPath(), 8, Coloring::Shaded},
                                           Case{"spot-levels", spotPath(), 8, Coloring::Levels},
                                           Case{"duck-shaded", duckPath(), 8, Coloring::Shaded},
                                           Case{"duck-levels", duckPath(), 8, Coloring::Levels},
                                           Case{"spot-texcoords", spotPath(), 8, Coloring::Texcoords},
                                           Case{"duck-texcoords", duckPath(), 8, Coloring::Texcoords}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                             std::string n = info.param.name;
                             n.erase(std::remove(n.begin(), n.end(), '-'), n.end());
                             return n;
                         });

// looprender draws its images with its own pipelines around the surface (scene_vk.h's
// ClientPipelines: surfaceStages, the documented layout, shade.frag), as an engine
// builds them. Same shader, same surface: its PNG must equal
// renderImage with the library's built-in pipelines pixel for pixel, on both paths,
// in each colouring and in wireframe.
class LooprenderPipelines : public VulkanTest {};

TEST_F(LooprenderPipelines, DrawTheBuiltInPipelinesImageBitForBit) {
    const Baked* b = baked(spotPath(), 2);
    ASSERT_NE(b, nullptr);
    auto surface = upload(*b);
    ASSERT_NE(surface, nullptr);
    const fs::path scratch = fs::path(::testing::TempDir()) / "looprender_pipelines";
    fs::create_directories(scratch);
    const std::string glb = (scratch / "spot.glb").string(), png = (scratch / "image.png").string();
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(writeAssetGlb(b->asset, bytes));
    ASSERT_TRUE(writeFileAtomic(glb, bytes.data(), bytes.size()));
    struct View {
        const char* color;
        Coloring coloring;
        DrawPath path;
        bool wireframe;
    };
    for (const View& v : {View{"shaded", Coloring::Shaded, DrawPath::Tessellator, false},
                          View{"levels", Coloring::Levels, DrawPath::Patterns, false},
                          View{"texcoords", Coloring::Texcoords, DrawPath::Patterns, false},
                          View{"levels", Coloring::Levels, DrawPath::Tessellator, true}}) {
        const char* path = v.path == DrawPath::Patterns ? "patterns" : "tessellator";
        SCOPED_TRACE(std::string(v.color) + ", " + path + (v.wireframe ? ", wireframe" : ""));
        if (v.wireframe && !gpu->handles().fillModeNonSolid) continue;
        std::vector<std::string> args = {
            glb,  "--tess",       "4",     "--color", v.color,  "--path",
            path, "--validation", "--png", png,       "--size", std::to_string(kSize) + "x" + std::to_string(kSize)};
        if (v.wireframe) args.push_back("--wireframe");
        RunResult render = runTool(LOOPRENDER_EXE, args, scratch);
        ASSERT_EQ(render.exitCode, 0) << render.err;
        const Image theirs = readPng(png);

        FrameSettings frame;
        frame.tessFactor = 4;
        frame.coloring = v.coloring;
        frame.path = v.path;
        frame.wireframe = v.wireframe;
        Image ours;
        const RenderSettings rs = defaultView(b->asset, frame);
        Status st = renderImage(*surface, rs, ours);
        ASSERT_TRUE(st) << st.message;
        ASSERT_EQ(theirs.width, ours.width);
        ASSERT_EQ(theirs.height, ours.height);
        size_t differing = 0;
        for (size_t i = 0; i < ours.rgba.size(); i += 4)
            differing += !std::equal(&ours.rgba[i], &ours.rgba[i] + 3, &theirs.rgba[i]);
        EXPECT_EQ(differing, 0u) << "pixels differ between looprender's pipelines and the built-in ones";
    }
    fs::remove_all(scratch);
}

// Whole scenes as a user draws them: loopbake, then looprender --color
// material (viewer/scene_render.cpp): node transforms, the file's camera,
// glTF materials with their textures, skins posed by an animation at a time.
struct SceneCase {
    const char* name;
    std::string input;
    std::vector<std::string> options;  // besides --color material --png --size
};

void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.name; }

class SceneImages : public ::testing::TestWithParam<SceneCase> {};

TEST_P(SceneImages, MatchWithinTolerance) {
    const SceneCase& c = GetParam();
    const fs::path scratch = fs::path(::testing::TempDir()) / (std::string("scene_images_") + c.name);
    fs::create_directories(scratch);
    const std::string glb = (scratch / "baked.glb").string(), png = (scratch / "image.png").string();
    RunResult bake = runTool(LOOPBAKE_EXE, {c.input, "-o", glb}, scratch);
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
    std::vector<std::string> args = {
        glb,     "--color", "material", "--validation",
        "--png", png,       "--size",   std::to_string(kSize) + "x" + std::to_string(kSize)};
    args.insert(args.end(), c.options.begin(), c.options.end());
    RunResult render = runTool(LOOPRENDER_EXE, args, scratch);
    ASSERT_EQ(render.exitCode, 0) << render.err;
    std::printf("[ figures  ] %s", render.out.c_str());
    Image actual = readPng(png);
    ASSERT_FALSE(actual.rgba.empty());
    checkGolden(c.name, actual);
    fs::remove_all(scratch);
}

std::string dataPath(const char* relative) { return std::string(LOOPTESS_TEST_DATA) + "/" + relative; }

INSTANTIATE_TEST_SUITE_P(
    Scenes, SceneImages,
    // The golden images are the tessellator path's; the Fox walks on the pattern path
    // too (its images differ from the tessellator's in 1 and 2 pixels).
    ::testing::Values(
        SceneCase{"scene-duck", duckPath(), {"--tess", "8", "--path", "tessellator"}},
        SceneCase{"scene-fox-walk-0",
                  dataPath("real/fox.glb"),
                  {"--tess", "4", "--animation", "1", "--time", "0", "--path", "patterns"}},
        SceneCase{"scene-fox-walk-0.35",
                  dataPath("real/fox.glb"),
                  {"--tess", "4", "--animation", "1", "--time", "0.35", "--path", "patterns"}},
        SceneCase{"scene-robot-wave-1",
                  dataPath("real/robotexpressive.glb"),
                  {"--tess", "2", "--animation", "12", "--time", "1", "--path", "tessellator"}},
        SceneCase{
            "scene-orientation", dataPath("scenes/OrientationTest.gltf"), {"--tess", "4", "--path", "tessellator"}},
        SceneCase{"scene-box-textured", dataPath("scenes/BoxTextured.gltf"), {"--tess", "4", "--path", "tessellator"}}),
    [](const ::testing::TestParamInfo<SceneCase>& info) {
        std::string n = info.param.name;
        n.erase(std::remove_if(n.begin(), n.end(), [](char ch) { return ch == '-' || ch == '.'; }), n.end());
        return n;
    });

}  // namespace
}  // namespace lt::test
