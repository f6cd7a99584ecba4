// tests/check/test_loopcheck_input_options.cpp -- how loopbake reads its input, end to
// end through both binaries: --boundary on OBJ and glTF input (loopcheck --source
// with the same --boundary passes; without it, M1 names both rules; a mesh that
// none leaves empty is a warning), and a polygon
// mesh the old fan triangulation made a fin of (two quads sharing two consecutive
// edges) passing loopcheck at F = 1, 3.3 and 8.
#include "gltf_fixture.h"
#include "tool_run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace input_options_test {

namespace fs = std::filesystem;
using lt::test::contains;
using lt::test::RunResult;

fs::path dir() { return lt::test::processTempDir("looptess_input_options"); }

fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir() / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
}

RunResult loopbake(const std::vector<std::string>& args) { return lt::test::runTool(LOOPBAKE_EXE, args, dir()); }

RunResult loopcheck(const fs::path& asset, const fs::path& source, const std::vector<std::string>& extra) {
    std::vector<std::string> args = {asset.string(), "--source", source.string(), "--tess", "1",
                                     "3.3",          "8",        "--rays",        "0",      "--no-validator"};
    args.insert(args.end(), extra.begin(), extra.end());
    return lt::test::runTool(LOOPCHECK_EXE, args, dir());
}

const char* const kQuadObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";

TEST(InputOptions, EveryBoundaryRuleOfAnObjPassesLoopcheck) {
    const fs::path source = write("quad.obj", kQuadObj);
    for (const char* rule : {"none", "edge", "edge-and-corner"}) {
        SCOPED_TRACE(rule);
        const fs::path asset = dir() / (std::string("quad-") + rule + ".glb");
        RunResult r = loopbake({source.string(), "-o", asset.string(), "--boundary", rule});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        // With none, every face of the open quad touches the boundary: nothing is drawn,
        // which loopbake says (it said nothing before).
        if (std::string(rule) == "none")
            EXPECT_EQ(r.err, "loopbake: warning: " + source.string() +
                                 ": draws no face: each of its 2 faces is a hole or, with boundary interpolation "
                                 "none, touches the boundary\n");
        else
            EXPECT_TRUE(r.err.empty()) << r.err;
        r = loopcheck(asset, source, {"--boundary", rule});
        EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    }
    // Read without the option, the source has edge-only: M1 says what to do.
    const RunResult r = loopcheck(dir() / "quad-edge-and-corner.glb", source, {});
    EXPECT_EQ(r.exitCode, 3) << r.out;
    EXPECT_TRUE(contains(r.out, "error M1: --source " + source.string() +
                                    ": the source's boundary rule is edge, the asset's edge-and-corner (baked with "
                                    "loopbake --boundary? give loopcheck the same)"))
        << r.out;
}

TEST(InputOptions, BoundaryOverridesAnObjTagWithAWarning) {
    const fs::path source = write("tagged.obj", std::string(kQuadObj) + "t interpolateboundary 1/0/0 2\n");
    const fs::path asset = dir() / "tagged.glb";
    RunResult r = loopbake({source.string(), "-o", asset.string(), "--boundary", "edge-and-corner"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "loopbake: warning: " + source.string() +
                                    ": line 7: 'interpolateboundary' tag says edge; using --boundary edge-and-corner"))
        << r.err;
    EXPECT_EQ(loopcheck(asset, source, {"--boundary", "edge-and-corner"}).exitCode, 0);
    r = loopbake({source.string(), "-o", asset.string(), "--boundary", "edge-only"});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.err, "--boundary must be none, edge or edge-and-corner, not 'edge-only'")) << r.err;
}

TEST(InputOptions, BoundaryAppliesToGltfMeshes) {
    gltftest::Bytes bin;
    const gltftest::Json j =
        gltftest::triangles(bin, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3}, {0, 0, 1, 0, 1, 1, 0, 1});
    const gltftest::Bytes glb = gltftest::makeGlb(j, bin);
    const fs::path source = dir() / "quad-in.glb", asset = dir() / "quad-gltf.glb";
    std::ofstream(source, std::ios::binary)
        .write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
    RunResult r = loopbake({source.string(), "-o", asset.string(), "--boundary", "edge-and-corner"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = loopcheck(asset, source, {"--boundary", "edge-and-corner"});
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    r = loopcheck(asset, source, {});
    EXPECT_EQ(r.exitCode, 3) << r.out;
    EXPECT_TRUE(contains(r.out, "the source's boundary rule is edge, the asset's edge-and-corner")) << r.out;
}

// The square cut along b-c-d into two quads sharing b-c and c-d (c of valence 2), each
// written so that a fan from its first corner splits it along b-d: the old reader made
// the fin (b c d) (d c b), with zero normals (N1) and edges of four faces (W2).
TEST(InputOptions, QuadsSharingTwoEdgesPassLoopcheck) {
    const fs::path source =
        write("valence2.obj", "v 0 0 0\nv 2 0 0\nv 1 1 0\nv 0 2 0\nv 2 2 0\nf 2 3 4 1\nf 4 3 2 5\n");
    const fs::path asset = dir() / "valence2.glb";
    RunResult r = loopbake({source.string(), "-o", asset.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "loopbake: warning: " + source.string() +
                         ": 2 polygons with more than 3 sides were triangulated (first at line 6)\n");
    r = loopcheck(asset, source, {});
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_FALSE(contains(r.out, "N1")) << r.out;
    EXPECT_FALSE(contains(r.out, "W2")) << r.out;
}

}  // namespace input_options_test
