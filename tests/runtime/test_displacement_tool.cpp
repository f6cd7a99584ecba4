// test_displacement_tool.cpp -- displacement maps at the edges: PNG decoding
// (lt::decodeGrayPng: 8- and 16-bit gray, gray + alpha, refusals) and
// `loopbake IN --displacement MAP.png --scale S [--bias B] [--displacement-resolution R]`
// end to end (exit codes, -v and --json statistics, determinism, the asset read back).
#include "looptess/tools/baker.h"

#include "displacement_map.h"
#include "tool_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using Bytes = std::vector<uint8_t>;
using lt::test::RunResult;

const std::string kSpot = std::string(LOOPTESS_TEST_DATA) + "/spot.obj";
const std::string kFandisk = std::string(LOOPTESS_CORPUS_DIR) + "/meshes/fandisk.obj";  // no UVs

Bytes readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& path, const Bytes& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    ASSERT_TRUE(out.good()) << path;
}

fs::path scratchDir(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / ("looptess_displacement_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// An image written by stb_image_write (8 bits, `comp` channels), read back.
Bytes stbPng(const fs::path& dir, int comp) {
    const int w = 5, h = 3;
    std::vector<uint8_t> pixels(size_t(w) * h * comp);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t(i * 37 + 11);
    const fs::path path = dir / ("stb" + std::to_string(comp) + ".png");
    EXPECT_NE(stbi_write_png(path.string().c_str(), w, h, comp, pixels.data(), w * comp), 0);
    return readBytes(path);
}

TEST(DisplacementPng, SixteenBitTexelsExactly) {
    const Bytes png = lt::test::patternPng(37, 19, 16);
    lt::GrayImage image;
    const lt::Status st = lt::decodeGrayPng(png.data(), png.size(), "p.png", image);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(image.width, 37u);
    EXPECT_EQ(image.height, 19u);
    EXPECT_EQ(image.bitDepth, 16u);
    for (uint32_t y = 0; y < 19; ++y)
        for (uint32_t x = 0; x < 37; ++x)
            ASSERT_EQ(image.texels[y * 37 + x], lt::test::patternTexel(x, y, 37, 19)) << x << ", " << y;
    EXPECT_EQ(png, lt::test::patternPng(37, 19, 16));  // deterministic bytes
}

TEST(DisplacementPng, EightBitScaledBy257) {
    const Bytes png = lt::test::patternPng(8, 8, 8);
    lt::GrayImage image;
    ASSERT_TRUE(lt::decodeGrayPng(png.data(), png.size(), "p8.png", image));
    EXPECT_EQ(image.bitDepth, 8u);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x)
            EXPECT_EQ(image.texels[y * 8 + x], (lt::test::patternTexel(x, y, 8, 8) + 128) / 257 * 257);
}

TEST(DisplacementPng, StbWrittenGrayAndGrayAlphaDecode) {
    const fs::path dir = scratchDir("png");
    for (int comp : {1, 2}) {
        const Bytes png = stbPng(dir, comp);
        lt::GrayImage image;
        const lt::Status st = lt::decodeGrayPng(png.data(), png.size(), "stb.png", image);
        ASSERT_TRUE(st) << st.message;
        ASSERT_EQ(image.texels.size(), 15u);
        for (size_t i = 0; i < 15; ++i)
            EXPECT_EQ(image.texels[i], uint8_t(i * comp * 37 + 11) * 257) << i;  // alpha dropped
    }
}

TEST(DisplacementPng, Refusals) {
    const fs::path dir = scratchDir("refusals");
    lt::GrayImage image;
    for (int comp : {3, 4}) {
        const Bytes png = stbPng(dir, comp);
        const lt::Status st = lt::decodeGrayPng(png.data(), png.size(), "color.png", image);
        EXPECT_EQ(st.code, lt::Status::Unsupported) << st.message;
        EXPECT_NE(st.message.find("color.png: a RGB"), std::string::npos) << st.message;
        EXPECT_NE(st.message.find("must be grayscale"), std::string::npos) << st.message;
    }
    const Bytes garbage = {'n', 'o', 't', ' ', 'a', ' ', 'p', 'n', 'g', '!'};
    EXPECT_EQ(lt::decodeGrayPng(garbage.data(), garbage.size(), "g.png", image).code, lt::Status::BadInput);
    Bytes png = lt::test::patternPng(16, 16, 16);
    const Bytes truncated(png.begin(), png.begin() + std::ptrdiff_t(png.size() / 2));
    lt::Status st = lt::decodeGrayPng(truncated.data(), truncated.size(), "t.png", image);
    EXPECT_EQ(st.code, lt::Status::BadInput) << st.message;
    png[16] = 0x7f;  // width 2^30 + 16: over the texel limit, refused before decoding
    st = lt::decodeGrayPng(png.data(), png.size(), "big.png", image);
    EXPECT_EQ(st.code, lt::Status::BadInput);
    EXPECT_NE(st.message.find("more than the limit"), std::string::npos) << st.message;
    EXPECT_EQ(lt::decodeGrayPng(nullptr, 0, "empty.png", image).code, lt::Status::BadInput);
}

// --- loopbake --displacement ---------------------------------------------------------------

RunResult loopbake(const std::vector<std::string>& args, const fs::path& scratch) {
    return lt::test::runTool(LOOPBAKE_EXE, args, scratch);
}

TEST(DisplacementTool, BakesSpotWithAMap) {
    const fs::path dir = scratchDir("tool");
    const fs::path map = dir / "map.png", out = dir / "spot.glb", out2 = dir / "spot2.glb", report = dir / "r.json";
    writeBytes(map, lt::test::patternPng(256, 256, 16));
    const std::vector<std::string> common = {kSpot,        "--max-depth", "2",    "--displacement",
                                             map.string(), "--scale",     "0.05", "--bias=-0.025"};
    std::vector<std::string> args = common;
    args.insert(args.end(), {"-o", out.string(), "-v", "--json", report.string()});
    RunResult r = loopbake(args, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("displacement: " + map.string() + ", 256x256, 16-bit; resolution "), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(", displacement "), std::string::npos) << r.err;

    const nlohmann::json j = nlohmann::json::parse(lt::test::readText(report));
    const uint32_t R = j["settings"]["displacement"]["resolution"].get<uint32_t>();
    EXPECT_EQ(j["settings"]["displacement"]["mapBitDepth"], 16);
    EXPECT_GT(j["tableBytes"]["displacement"].get<size_t>(), 0u);

    const Bytes bytes = readBytes(out);
    lt::Asset asset;
    const lt::Status st = lt::readAssetGlb(bytes.data(), bytes.size(), out.string(), asset);
    ASSERT_TRUE(st) << st.message;
    ASSERT_TRUE(asset.displacement.present());
    EXPECT_EQ(asset.displacement.resolution, R);
    EXPECT_EQ(asset.displacement.scale, 0.05f);
    EXPECT_EQ(asset.displacement.bias, -0.025f);
    EXPECT_EQ(asset.displacement.values.size(), j["settings"]["displacement"]["samples"].get<size_t>());

    args = common;  // the same command again: the same bytes
    args.insert(args.end(), {"-o", out2.string()});
    ASSERT_EQ(loopbake(args, dir).exitCode, 0);
    EXPECT_EQ(readBytes(out2), bytes);

    args = common;  // an explicit resolution
    args.insert(args.end(), {"-o", out2.string(), "--displacement-resolution", "4"});
    ASSERT_EQ(loopbake(args, dir).exitCode, 0);
    lt::Asset four;
    const Bytes fourBytes = readBytes(out2);
    ASSERT_TRUE(lt::readAssetGlb(fourBytes.data(), fourBytes.size(), "four.glb", four));
    EXPECT_EQ(four.displacement.resolution, 4u);
}

TEST(DisplacementTool, ExitCodes) {
    const fs::path dir = scratchDir("exit");
    const fs::path map = dir / "map.png", rgb = dir / "rgb.png", out = dir / "o.glb";
    writeBytes(map, lt::test::patternPng(16, 16, 8));
    writeBytes(rgb, stbPng(dir, 3));
    const std::string m = map.string(), o = out.string();
    struct Case {
        std::vector<std::string> args;
        int exitCode;
        std::string message;
    };
    const Case cases[] = {
        {{kSpot, "-o", o, "--displacement", m}, 1, "--displacement needs --scale"},
        {{kSpot, "-o", o, "--scale", "1"}, 1, "need --displacement"},
        {{kSpot, "-o", o, "--displacement", m, "--scale", "nan"}, 1, "--scale must be a finite number"},
        {{kSpot, "-o", o, "--displacement", m, "--scale", "1", "--displacement-resolution", "3"},
         1,
         "power of two from 1 to 64"},
        {{kSpot, "-o", o, "--displacement", m, "--scale", "1", "--displacement-resolution", "128"},
         1,
         "power of two from 1 to 64"},
        {{kSpot, "-o", o, "--displacement", rgb.string(), "--scale", "1"}, 3, "must be grayscale"},
        {{kSpot, "-o", o, "--displacement", (dir / "missing.png").string(), "--scale", "1"}, 2, "missing.png"},
        {{kFandisk, "-o", o, "--max-depth", "1", "--displacement", m, "--scale", "1"}, 2, "needs texture coordinates"},
    };
    for (const Case& c : cases) {
        const RunResult r = loopbake(c.args, dir);
        EXPECT_EQ(r.exitCode, c.exitCode) << c.message << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out)) << "a failed run left " << out;
    }
}

}  // namespace
