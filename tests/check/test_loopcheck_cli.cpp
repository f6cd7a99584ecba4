// tests/check/test_loopcheck_cli.cpp -- the loopcheck command on corpus assets baked
// with the loopbake binary (structure, accuracy against OpenSubdiv, rays, --gpu,
// --no-watertight, --threads) and on deliberately broken ones (exit 2 naming the
// problem). Every corpus asset passing, displaced and not: test_loopcheck_corpus.cpp.
#include "format_fixture.h"  // fmttest::Glb: editing a GLB's JSON and BIN
#include "sanitizer.h"
#include "tool_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using lt::test::RunResult;

const fs::path kCorpus = LOOPTESS_CORPUS_DIR;

class LoopcheckCli : public ::testing::Test {
protected:
    static fs::path dir() {
        static const fs::path d = [] {
            fs::path p = fs::temp_directory_path() / ("looptess_loopcheck_" + std::to_string(getpid()));
            fs::create_directories(p);
            return p;
        }();
        return d;
    }
    static void TearDownTestSuite() { fs::remove_all(dir()); }

    // Bakes a corpus shape (opensubdiv-loop/NAME.obj) at depth 3 with loopbake, once.
    // `plain`: --compress none, for tests that edit table accessors in place.
    static fs::path bake(const std::string& name, bool plain = false) {
        const fs::path out = dir() / (name + (plain ? "_plain.glb" : ".glb"));
        if (!fs::exists(out)) {
            const RunResult r = lt::test::runTool(
                LOOPBAKE_EXE,
                {source(name).string(), "-o", out.string(), "--max-depth", "3", "--compress", plain ? "none" : "fast"},
                dir());
            EXPECT_EQ(r.exitCode, 0) << r.err;
        }
        return out;
    }
    static fs::path source(const std::string& name) { return kCorpus / "opensubdiv-loop" / (name + ".obj"); }
    static RunResult loopcheck(const std::vector<std::string>& args) {
        return lt::test::runTool(LOOPCHECK_EXE, args, dir());
    }
    static Json report(const fs::path& file) {
        std::ifstream in(file);
        return Json::parse(in, nullptr, false);
    }
    // Writes `bytes` as a new asset file and runs loopcheck on it: exit 2, and the
    // verdict names `expected`.
    static void expectInvalid(const std::vector<uint8_t>& bytes, const std::string& name, const std::string& expected) {
        const fs::path file = dir() / (name + ".glb");
        std::ofstream(file, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        const RunResult r = loopcheck({file.string(), "--no-validator", "--json", (dir() / (name + ".json")).string()});
        EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
        EXPECT_NE(r.out.find(expected), std::string::npos) << "expected '" << expected << "' in:\n" << r.out;
        EXPECT_NE(r.out.find("INVALID"), std::string::npos) << r.out;
        Json j = report(dir() / (name + ".json"));
        EXPECT_EQ(j.value("result", ""), "invalid");
        EXPECT_FALSE(j["structure"].value("valid", true));
    }
    static std::vector<uint8_t> bytesOf(const fs::path& file) {
        std::ifstream in(file, std::ios::binary);
        return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
};

// A JSON boolean (false when absent or not a boolean).
bool yes(const Json& x) { return x.is_boolean() && x.get<bool>(); }

// Every finding of `j` of severity error, by id.
std::set<std::string> errorIds(Json& j) {
    std::set<std::string> ids;
    for (Json& f : j["findings"])
        if (f["severity"] == "error") ids.insert(f["id"].get<std::string>());
    return ids;
}

TEST_F(LoopcheckCli, CorpusAssetStructureAccuracyRays) {
    const fs::path asset = bake("loop_icos_semisharp"), json = dir() / "icos.json";
    const RunResult r = loopcheck({asset.string(), "--source", source("loop_icos_semisharp").string(), "--rays",
                                   "20000", "--tess", "1", "3.3:odd", "5", "screen=4:odd", "--json", json.string()});
    ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 3) << r.out << r.err;
    Json j = report(json);
    ASSERT_TRUE(j.is_object()) << r.out;
    EXPECT_TRUE(yes(j["structure"]["valid"]));
    EXPECT_TRUE(yes(j["source"]["matches"]));
    EXPECT_TRUE(yes(j["controlMesh"]["closed"]));
    EXPECT_EQ(j["validator"]["state"], "ran") << "the Khronos glTF-Validator: scripts/setup-debian.sh installs it";
    EXPECT_TRUE(j["validator"].value("pass", false)) << j["validator"].dump();
    EXPECT_EQ(j["reference"]["factor"], 8.0);  // 2^maxDepth
    ASSERT_EQ(j["tessellations"].size(), 4u);
    for (Json& t : j["tessellations"]) {
        SCOPED_TRACE(t["name"].get<std::string>());
        Json& a = t["accuracy"];
        EXPECT_GT(a["sampled"].get<uint64_t>(), 0u);
        EXPECT_EQ(a["positionFailures"], 0) << a.dump();
        EXPECT_EQ(a["normalFailures"], 0) << a.dump();
        EXPECT_LE(a["maxPositionError"].get<double>(), 1e-5);
        EXPECT_EQ(t["weld"]["unexpectedNonManifoldEdges"], 0);
        EXPECT_EQ(t["weld"]["misorientedEdges"], 0);
        Json& y = t["rays"];
        ASSERT_TRUE(yes(y["ran"])) << y.dump();
        EXPECT_EQ(y["rays"], 20000);
        EXPECT_GT(y["origins"].get<uint64_t>(), 100u);
        if (yes(y["distances"]["checked"])) { EXPECT_EQ(y["distances"]["failures"], 0) << y.dump(); }
    }
    // F = 5 is not twice as fine as the depth-3 reference at F = 8: not compared.
    EXPECT_FALSE(yes(j["tessellations"][2]["rays"]["distances"]["checked"]));
    EXPECT_TRUE(yes(j["tessellations"][0]["rays"]["distances"]["checked"]));
    EXPECT_TRUE(errorIds(j).empty()) << r.out;
    EXPECT_EQ(r.exitCode, 0);
}

// --threads splits the CPU evaluation differently and changes no finding or figure.
TEST_F(LoopcheckCli, ThreadsGiveTheSameReport) {
    const fs::path asset = bake("loop_icos_semisharp");
    Json reports[2];
    const char* counts[2] = {"1", "3"};
    for (int k = 0; k < 2; ++k) {
        const fs::path json = dir() / (std::string("threads") + counts[k] + ".json");
        const RunResult r =
            loopcheck({asset.string(), "--source", source("loop_icos_semisharp").string(), "--rays", "2000", "--tess",
                       "1", "5", "screen=4:odd", "--no-validator", "--threads", counts[k], "--json", json.string()});
        ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
        reports[k] = report(json);
    }
    ASSERT_EQ(reports[0]["tessellations"].size(), 3u);
    for (size_t t = 0; t < 3; ++t)
        for (const char* part : {"accuracy", "weld", "rays", "normals"})
            EXPECT_EQ(reports[0]["tessellations"][t][part], reports[1]["tessellations"][t][part]) << t << " " << part;
    EXPECT_EQ(loopcheck({asset.string(), "--threads", "lots"}).exitCode, 1);
}

// Sharp edges by angle beside the shapes' own semi-sharp ones: corners with two
// infinitely sharp edges and a semi-sharp one (the baker's sector stencils; before:
// A1 up to 6% of the diagonal and an R2 failure), OpenSubdiv's inward normal at a
// sector wider than 180 degrees (its sign is a convention there), corners whose
// sector holds several faces (each face its own normal, compared with the face's
// corner refined: OsdCornerNormals; before: A1, 0.4 degrees, and on spot a corner
// normal 92 degrees behind its F = 1 triangle, N1), and PatchTable's normal 21
// degrees off at a base corner on spot (a crease vertex between a dart's end and a
// corner: the oracle's normal by differences there).
TEST_F(LoopcheckCli, CreaseAnglesBesideSemiSharpEdges) {
    // Fewer rays under ASan (72-81 s there with 30,000; 21 s in the release run).
    const std::vector<std::string> all = {
        "--rays", lt::test::kAsan ? "3000" : "30000", "--tess", "1", "2", "1.7:odd", "4", "screen=2"};
    std::vector<std::pair<fs::path, std::vector<std::string>>> cases = {{source("loop_cube_creases0"), all},
                                                                        {source("loop_cubes_semisharp"), all},
                                                                        {source("loop_icos_semisharp"), all}};
    // A real mesh in the release run (under ASan its bake and check took 39 of the test's 67 s).
    if (!lt::test::kAsan) cases.push_back({kCorpus / "meshes" / "spot.obj", {"--rays", "0", "--tess", "1"}});
    for (const auto& [input, extra] : cases) {
        SCOPED_TRACE(input.filename().string());
        const fs::path asset = dir() / (input.stem().string() + "_angle.glb");
        const RunResult bake =
            lt::test::runTool(LOOPBAKE_EXE, {input.string(), "-o", asset.string(), "--crease-angle", "25"}, dir());
        ASSERT_EQ(bake.exitCode, 0) << bake.err;
        std::vector<std::string> args = {asset.string(),   "--source", input.string(),
                                         "--crease-angle", "25",       "--no-validator"};
        args.insert(args.end(), extra.begin(), extra.end());
        const RunResult r = loopcheck(args);
        EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    }
}

TEST_F(LoopcheckCli, OpenMeshesSkipRaysAndKeepTheirBoundary) {
    const fs::path asset = bake("loop_saddle_edgeonly"), json = dir() / "saddle.json";
    const RunResult r =
        loopcheck({asset.string(), "--rays", "1000", "--tess", "4", "--no-validator", "--json", json.string()});
    ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 3) << r.out << r.err;
    Json j = report(json);
    EXPECT_FALSE(yes(j["controlMesh"]["closed"]));
    Json& t = j["tessellations"][0];
    EXPECT_FALSE(yes(t["rays"]["ran"]));
    EXPECT_NE(t["rays"]["skipped"].get<std::string>().find("open"), std::string::npos);
    EXPECT_GT(t["weld"]["boundaryEdges"].get<uint64_t>(), 0u);  // 4 segments per boundary edge, on the boundary
    EXPECT_EQ(j["settings"]["tessellations"][0], "F=4 equal");
}

TEST_F(LoopcheckCli, NoWatertightOpensEdges) {
    const fs::path asset = bake("loop_icos_semisharp"), json = dir() / "loose.json";
    const RunResult r = loopcheck({asset.string(), "--no-watertight", "--tess", "3.3:odd", "--rays", "0",
                                   "--no-validator", "--json", json.string()});
    EXPECT_EQ(r.exitCode, 3) << r.out << r.err;
    Json j = report(json);
    EXPECT_FALSE(yes(j["settings"]["watertight"]));
    EXPECT_FALSE(yes(j["tessellations"][0]["watertight"]));
    EXPECT_GT(j["tessellations"][0]["weld"]["crackEdges"].get<uint64_t>(), 0u);
    EXPECT_EQ(errorIds(j), std::set<std::string>{"W1"});
}

TEST_F(LoopcheckCli, SourceOfAnotherMeshFails) {
    const fs::path json = dir() / "other.json";
    const RunResult r =
        loopcheck({bake("loop_icos_semisharp").string(), "--source", source("loop_tetrahedron").string(), "--tess", "1",
                   "--rays", "0", "--no-validator", "--json", json.string()});
    EXPECT_EQ(r.exitCode, 3) << r.out << r.err;
    EXPECT_NE(r.out.find("error M1"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("faces"), std::string::npos) << r.out;
    EXPECT_FALSE(yes(report(json)["source"]["matches"]));
}

TEST_F(LoopcheckCli, GpuCaptureIsChecked) {
#ifdef LOOPTESS_ASAN
    GTEST_SKIP() << "the sanitizer build does not drive the Vulkan device (scripts/dev.sh, sanitize)";
#endif
    const fs::path json = dir() / "gpu.json";
    const RunResult r = loopcheck({bake("loop_icosahedron").string(), "--gpu", "--tess", "2", "screen=4:odd", "--rays",
                                   "2000", "--no-validator", "--json", json.string()});
    ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 3) << r.out << r.err;
    Json j = report(json);
    EXPECT_TRUE(yes(j["settings"]["gpu"]));
    ASSERT_EQ(j["tessellations"].size(), 4u);
    for (Json& t : j["tessellations"]) {
        SCOPED_TRACE(t["name"].get<std::string>() + " " + t["path"].get<std::string>());
        EXPECT_FALSE(t.contains("error")) << t.dump();
        EXPECT_GT(t["triangles"].get<uint64_t>(), 0u);
        EXPECT_TRUE(yes(t["rays"]["ran"]));
        if (t["path"] == "gpu") { EXPECT_GT(t["cpuComparison"]["cpuVertices"].get<uint64_t>(), 0u); }
    }
    EXPECT_TRUE(errorIds(j).empty()) << r.out;
    EXPECT_EQ(r.exitCode, 0);
}

// --piece-triangles: the CPU's evaluation in pieces of base faces and the GPU's capture
// in sessions, each checked as a piece and welded across (the memory limit does the
// same for a case too large): the same welded mesh as the whole, every base corner
// against OpenSubdiv, no hit distances (R4).
TEST_F(LoopcheckCli, PiecesAndCaptureSessionsAreChecked) {
    const fs::path whole = dir() / "whole.json", pieces = dir() / "pieces.json";
    std::vector<std::string> args = {bake("loop_cube_creases1").string(),
                                     "--source",
                                     source("loop_cube_creases1").string(),
                                     "--tess",
                                     "4",
                                     "--rays",
                                     "2000",
                                     "--no-validator"};
#ifndef LOOPTESS_ASAN  // the sanitizer build does not drive the Vulkan device
    args.push_back("--gpu");
#endif
    std::vector<std::string> inPieces = args;
    args.insert(args.end(), {"--json", whole.string()});
    inPieces.insert(inPieces.end(), {"--piece-triangles", "80", "--json", pieces.string()});
    const RunResult a = loopcheck(args), b = loopcheck(inPieces);
    EXPECT_EQ(a.exitCode, 0) << a.out << a.err;
    EXPECT_EQ(b.exitCode, 0) << b.out << b.err;
    Json w = report(whole), p = report(pieces);
    ASSERT_EQ(w["tessellations"].size(), p["tessellations"].size());
    for (size_t i = 0; i < p["tessellations"].size(); ++i) {
        Json &t = p["tessellations"][i], &u = w["tessellations"][i];
        SCOPED_TRACE(t["path"].get<std::string>());
        EXPECT_FALSE(u.contains("pieces"));
        EXPECT_TRUE(yes(u["rays"]["distances"]["checked"]));
        EXPECT_GE(t["pieces"].get<uint32_t>(), 2u);
        EXPECT_EQ(t["weld"]["weldedVertices"], u["weld"]["weldedVertices"]);
        EXPECT_EQ(t["weld"]["edges"], u["weld"]["edges"]);
        EXPECT_EQ(t["weld"]["openEdges"], 0);
        EXPECT_TRUE(yes(t["rays"]["ran"]));
        EXPECT_FALSE(yes(t["rays"]["distances"]["checked"]));
        EXPECT_NE(t["rays"]["distances"]["skipped"].get<std::string>().find("pieces"), std::string::npos);
        if (t["path"] == "cpu") { EXPECT_EQ(t["accuracy"]["corners"], u["accuracy"]["corners"]); }
    }
#ifndef LOOPTESS_ASAN
    EXPECT_NE(b.out.find("capture sessions"), std::string::npos) << b.out;
#endif
    EXPECT_NE(b.out.find("pieces of base faces"), std::string::npos) << b.out;
}

// The compute path's capture passes every check (watertightness, normals, rays) and
// equals, bit for bit, the CPU's evaluation of the same pattern points, whose accuracy
// against OpenSubdiv passes.
TEST_F(LoopcheckCli, ComputePathCaptureIsChecked) {
#ifdef LOOPTESS_ASAN
    GTEST_SKIP() << "the sanitizer build does not drive the Vulkan device (scripts/dev.sh, sanitize)";
#endif
    const fs::path json = dir() / "compute.json";
    const RunResult r = loopcheck({bake("loop_icos_semisharp").string(), "--source",
                                   source("loop_icos_semisharp").string(), "--gpu", "--path", "compute", "--tess", "3",
                                   "screen=4", "--rays", "2000", "--no-validator", "--json", json.string()});
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    Json j = report(json);
    EXPECT_EQ(j["settings"]["drawPath"], "compute");
    ASSERT_EQ(j["tessellations"].size(), 4u);
    for (Json& t : j["tessellations"]) {
        SCOPED_TRACE(t["name"].get<std::string>() + " " + t["path"].get<std::string>());
        if (t["path"] == "cpu") { EXPECT_GT(t["accuracy"]["sampled"].get<uint64_t>(), 0u); }
        if (t["path"] == "gpu") { EXPECT_EQ(t["cpuComparison"]["equalPositions"], t["cpuComparison"]["cpuVertices"]); }
    }
    EXPECT_TRUE(errorIds(j).empty()) << r.out;
}

TEST_F(LoopcheckCli, UnavailableValidatorWarnsUnlessStrict) {
    const std::vector<std::string> args = {
        bake("loop_tetrahedron").string(),   "--tess", "1", "--rays", "0", "--validator",
        (dir() / "no_validator.js").string()};
    const RunResult lenient = loopcheck(args);
    EXPECT_NE(lenient.out.find("warning V2"), std::string::npos) << lenient.out;
    EXPECT_EQ(lenient.exitCode, 0) << lenient.out;
    std::vector<std::string> strict = args;
    strict.push_back("--strict-validator");
    const RunResult r = loopcheck(strict);
    EXPECT_EQ(r.exitCode, 3) << r.out;
    EXPECT_NE(r.out.find("error V2"), std::string::npos) << r.out;
}

// --- broken assets: exit 2, naming the problem ----------------------------------------------

TEST_F(LoopcheckCli, ChangedControlIndexIsInvalid) {
    fmttest::Glb g(bytesOf(bake("loop_icos_semisharp", true)));
    Json& prim = fmttest::prim(g);
    const int indices = prim["indices"].get<int>();
    const int map = g.cage().contains("controlVertex") ? g.cage()["controlVertex"].get<int>() : -1;
    const size_t vertices = g.doc["accessors"][prim["attributes"]["POSITION"].get<int>()]["count"].get<size_t>();
    auto control = [&](uint32_t v) { return map < 0 ? v : g.index(map, v); };
    // Corner 0 of face 0 to a primitive vertex of another control vertex, in range.
    const uint32_t c[3] = {control(g.index(indices, 0)), control(g.index(indices, 1)), control(g.index(indices, 2))};
    uint32_t other = 0;
    while (other < vertices && (control(other) == c[0] || control(other) == c[1] || control(other) == c[2])) ++other;
    ASSERT_LT(other, vertices);
    g.setIndex(indices, 0, other);
    expectInvalid(g.bytes(), "control_index", "check C1");
}

TEST_F(LoopcheckCli, TableEntryOffByOneIsInvalid) {
    const std::vector<uint8_t> baked = bytesOf(bake("loop_icos_semisharp", true));
    {  // one past the end: level 0's vertex count (level 1's firstVertex) as an edge end
        fmttest::Glb g(baked);
        g.setIndex(g.accessor(1, "edgeVerts"), 0, g.ext()["levels"][1]["firstVertex"].get<uint32_t>());
        expectInvalid(g.bytes(), "edge_range", "levels[1].edgeVerts[0]: rule 25");
    }
    {  // in range: the first ring entry of level 1's first vertex point, plus one (or
        // the next vertex after it that is neither in the ring nor its parent)
        fmttest::Glb g(baked);
        const int acc = g.accessor(1, "vertexRing"), start = g.accessor(1, "vertexRingStart");
        const uint32_t parent = g.index(g.accessor(1, "vertexParent"), 0);
        std::set<uint32_t> ring;
        for (uint32_t j = g.index(start, 0); j < g.index(start, 1); ++j) ring.insert(g.index(acc, j));
        uint32_t v = g.index(acc, 0) + 1;
        while (ring.count(v) || v == parent) ++v;
        ASSERT_LT(v, g.ext()["levels"][1]["firstVertex"].get<uint32_t>());
        g.setIndex(acc, 0, v);
        expectInvalid(g.bytes(), "ring_entry", "levels[1].vertexRing[0]: check C2");
    }
}

TEST_F(LoopcheckCli, TruncatedBufferIsInvalid) {
    std::vector<uint8_t> b = bytesOf(bake("loop_icos_semisharp", true));
    b.resize(b.size() - 64);
    expectInvalid(b, "truncated", "rule 1");
    fmttest::Glb g(bytesOf(bake("loop_icos_semisharp", true)));
    g.bin.resize(g.bin.size() / 2);  // a consistent container whose buffer is cut
    expectInvalid(g.bytes(), "cut_buffer", "rule 4");
}

TEST_F(LoopcheckCli, UsageReportAndReadErrors) {
    const fs::path asset = bake("loop_tetrahedron");
    EXPECT_EQ(loopcheck({}).exitCode, 1);
    EXPECT_EQ(loopcheck({asset.string(), "--frobnicate"}).exitCode, 1);
    EXPECT_EQ(loopcheck({asset.string(), "--tess", "0.5"}).exitCode, 1);
    EXPECT_EQ(loopcheck({asset.string(), "--tess", "screen=9:oddish"}).exitCode, 1);
    EXPECT_EQ(loopcheck({asset.string(), asset.string()}).exitCode, 1);
    const RunResult missing = loopcheck({(dir() / "missing.glb").string(), "--no-validator"});
    EXPECT_EQ(missing.exitCode, 2) << missing.out;
    const RunResult unwritable = loopcheck({asset.string(), "--tess", "1", "--rays", "0", "--no-validator", "--json",
                                            (dir() / "no" / "such" / "dir" / "r.json").string()});
    EXPECT_EQ(unwritable.exitCode, 4) << unwritable.out << unwritable.err;
    // A report that would overwrite the asset (or the other report) is a usage error,
    // the asset untouched (before: exit 0, the asset replaced by the report).
    const auto before = fs::file_size(asset);
    const RunResult over = loopcheck({asset.string(), "--tess", "1", "--rays", "0", "--no-validator", "--json",
                                      (asset.parent_path() / "." / asset.filename()).string()});
    EXPECT_EQ(over.exitCode, 1) << over.out << over.err;
    EXPECT_NE(over.err.find("is also the asset"), std::string::npos) << over.err;
    EXPECT_EQ(fs::file_size(asset), before);
    const fs::path report = dir() / "r.out";
    EXPECT_EQ(loopcheck({asset.string(), "--json", report.string(), "--junit", report.string()}).exitCode, 1);
    const RunResult help = loopcheck({"--help"});
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.out.find("exit codes"), std::string::npos);
}

}  // namespace
