// test_bake_files.cpp -- baked files end to end: a byte-pinned golden file, determinism
// (in-process and through the loopbake binary), the Khronos glTF-Validator on every
// OpenSubdiv corpus shape plus spot and the Duck, GLB read/write round trips, and
// the --compress settings.
//
// Golden file: tests/data/golden/README.md (LOOPTESS_UPDATE_GOLDEN=1 rewrites it).
#include "looptess/tools/baker.h"

#include "sanitizer.h"
#include "tool_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using Json = nlohmann::json;
using Bytes = std::vector<uint8_t>;

namespace {

const fs::path kData = LOOPTESS_TEST_DATA;
const fs::path kCorpus = LOOPTESS_CORPUS_DIR;
const std::string kGoldenShape = "loop_icos_semisharp";  // tests/data/<shape>.obj
const std::string kGoldenDepth = "3";

Bytes readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

using lt::test::readText;
using lt::test::RunResult;

bool writeBytes(const fs::path& path, const Bytes& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return bool(out.flush());
}

RunResult loopbake(const std::vector<std::string>& args, const fs::path& scratch) {
    return lt::test::runTool(LOOPBAKE_EXE, args, scratch);
}

// Offset of the first byte where `a` and `b` differ (the shorter size when one is a
// prefix of the other), or npos when they are equal.
size_t firstDifference(const Bytes& a, const Bytes& b) {
    const size_t n = std::min(a.size(), b.size());
    for (size_t i = 0; i < n; ++i)
        if (a[i] != b[i]) return i;
    return a.size() == b.size() ? std::string::npos : n;
}

std::string describeDifference(const Bytes& expected, const Bytes& actual) {
    const size_t at = firstDifference(expected, actual);
    if (at == std::string::npos) return "identical";
    auto byteAt = [at](const Bytes& b) {
        if (at >= b.size()) return std::string("end of file");
        char buf[8];
        std::snprintf(buf, sizeof buf, "0x%02x", unsigned(b[at]));
        return std::string(buf);
    };
    std::ostringstream s;
    s << "first differing byte at offset " << at << " (expected " << byteAt(expected) << ", got " << byteAt(actual)
      << "); sizes " << expected.size() << " vs " << actual.size() << " bytes";
    return s.str();
}

// parseObj + checkInput + bake + writeAssetGlb, as loopbake does (without its I/O).
lt::Status bakeObj(const fs::path& obj, int maxDepth, Bytes& bytes) {
    lt::InputMesh mesh;
    lt::Status st = lt::parseObj(readText(obj), obj.string(), lt::InputOptions{}, mesh);
    if (st) st = lt::checkInput(mesh, obj.string());
    lt::Asset asset;
    lt::BakeSettings settings;
    settings.maxDepth = maxDepth;
    if (st) st = lt::bake(mesh, settings, asset);
    if (st) st = lt::writeAssetGlb(asset, bytes);
    return st;
}

// Under ASan every other shape (the two corpus sweeps below took 61 s there with all).
std::vector<fs::path> corpusShapes() {
    std::vector<fs::path> files;
    const fs::path dir = kCorpus / "opensubdiv-loop";
    if (fs::is_directory(dir))
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".obj") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return lt::test::asanSample(std::move(files), 2);
}

// Fails (never skips) when the Khronos glTF-Validator cannot run.
void requireValidator() {
    ASSERT_EQ(std::system("command -v node >/dev/null 2>&1"), 0)
        << "node is not installed, so the Khronos glTF-Validator cannot run: run "
           "scripts/setup-debian.sh (installs nodejs, npm and apps/loopcheck/validator's npm packages)";
    const fs::path module = fs::path(VALIDATOR_JS).parent_path() / "node_modules" / "gltf-validator";
    ASSERT_TRUE(fs::is_directory(module))
        << module << " is missing: run scripts/setup-debian.sh (npm install in apps/loopcheck/validator)";
}

// Runs `node VALIDATOR_JS file` and requires 0 errors and 0 warnings; on failure the
// message lists every error and warning (code, pointer, message).
void expectKhronosValid(const fs::path& file, const fs::path& scratch) {
    const RunResult r = lt::test::runTool("node", {VALIDATOR_JS, file.string()}, scratch);
    const Json report = Json::parse(r.out, nullptr, false);
    ASSERT_TRUE(!report.is_discarded() && report.contains("issues"))
        << "glTF-Validator did not report on " << file << " (exit " << r.exitCode << "):\n"
        << r.err << r.out;
    const Json& issues = report["issues"];
    const int errors = issues.value("numErrors", -1), warnings = issues.value("numWarnings", -1);
    std::string codes;
    for (const Json& m : issues.value("messages", Json::array())) {
        const int severity = m.value("severity", -1);  // 0 error, 1 warning, 2 info, 3 hint
        if (severity == 0 || severity == 1)
            codes += std::string("\n  ") + (severity == 0 ? "error " : "warning ") + m.value("code", "?") + " at " +
                     m.value("pointer", "?") + ": " + m.value("message", "");
    }
    EXPECT_EQ(errors, 0) << file << codes;
    EXPECT_EQ(warnings, 0) << file << codes;
    EXPECT_EQ(r.exitCode, errors == 0 && warnings == 0 ? 0 : 1) << r.err;
}

// The file reads back with readAssetGlb and re-writes to the same bytes (a baked OBJ;
// a baked glTF keeps its scene: test_scene_bake.cpp).
void expectRoundTrip(const Bytes& bytes, const std::string& name) {
    lt::Asset asset;
    lt::Status st = lt::readAssetGlb(bytes.data(), bytes.size(), name, asset);
    ASSERT_TRUE(st) << st.message;
    Bytes again;
    st = lt::writeAssetGlb(asset, again);
    ASSERT_TRUE(st) << st.message;
    EXPECT_TRUE(again == bytes) << name
                                << ": read + write round trip changed the file: " << describeDifference(bytes, again);
}

class BakeFiles : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ =
            fs::temp_directory_path() / ("looptess_test_bake_files_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(root_);
        fs::create_directories(root_);
        ASSERT_TRUE(fs::exists(LOOPBAKE_EXE)) << LOOPBAKE_EXE << " is missing: build the loopbake target";
    }
    void TearDown() override { fs::remove_all(root_); }

    fs::path root_;
};

// ---- 1. golden file -------------------------------------------------------------------

TEST_F(BakeFiles, GoldenFile) {
    const fs::path input = kData / (kGoldenShape + ".obj");
    const fs::path golden = kData / "golden" / (kGoldenShape + ".glb");
    const fs::path out = root_ / "golden.glb";
    const RunResult r = loopbake({input.string(), "-o", out.string(), "--max-depth", kGoldenDepth}, root_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Bytes baked = readBytes(out);
    ASSERT_FALSE(baked.empty());

    const std::string how = "(re)generate it with\n  LOOPTESS_UPDATE_GOLDEN=1 " +
                            fs::read_symlink("/proc/self/exe").string() +
                            " --gtest_filter=BakeFiles.GoldenFile\n"
                            "and commit the new file (see tests/data/golden/README.md)";
    const char* update = std::getenv("LOOPTESS_UPDATE_GOLDEN");
    if (update && std::string(update) == "1") {
        fs::create_directories(golden.parent_path());
        ASSERT_TRUE(writeBytes(golden, baked)) << "cannot write " << golden;
        std::cout << "LOOPTESS_UPDATE_GOLDEN=1: rewrote " << golden.string() << " (" << baked.size()
                  << " bytes) instead of comparing; review and commit it\n";
        RecordProperty("golden_updated", golden.string());
        return;
    }
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing; " << how;
    const Bytes expected = readBytes(golden);
    EXPECT_TRUE(baked == expected) << "loopbake " << input.string() << " --max-depth " << kGoldenDepth
                                   << " no longer matches " << golden.string() << ": "
                                   << describeDifference(expected, baked) << ";\nif the change is intended, " << how;
    ASSERT_NO_FATAL_FAILURE(requireValidator());
    expectKhronosValid(golden, root_);
    expectRoundTrip(expected, golden.string());
}

// ---- 2. determinism -------------------------------------------------------------------

// In-process: every shape that passes the checks (and the golden shape) bakes to the
// same bytes twice, and through the binary to the same bytes as in-process.
TEST_F(BakeFiles, InProcessBakeIsDeterministic) {
    std::vector<fs::path> shapes = corpusShapes();
    shapes.push_back(kData / (kGoldenShape + ".obj"));
    size_t baked = 0;
    for (const fs::path& obj : shapes) {
        SCOPED_TRACE(obj.string());
        Bytes first, second;
        if (!bakeObj(obj, 3, first)) continue;  // rejected: see CorpusBakesOrFailsClearly
        ASSERT_TRUE(bakeObj(obj, 3, second));
        EXPECT_TRUE(first == second) << describeDifference(first, second);
        ++baked;
    }
    EXPECT_GT(baked, 0u);

    const fs::path obj = kData / (kGoldenShape + ".obj"), out = root_ / "bin.glb";
    Bytes inProcess;
    ASSERT_TRUE(bakeObj(obj, 3, inProcess));
    const RunResult r = loopbake({obj.string(), "-o", out.string(), "--max-depth", "3"}, root_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Bytes binary = readBytes(out);
    EXPECT_TRUE(binary == inProcess) << "loopbake vs in-process: " << describeDifference(inProcess, binary);
}

// Through the binary: the same command twice gives identical GLB and --json bytes
// (an OBJ with tags and UVs, and a glTF input whose vertices are welded).
TEST_F(BakeFiles, BinaryBakeAndJsonReportAreDeterministic) {
    const std::vector<std::vector<std::string>> cases = {
        {(kData / (kGoldenShape + ".obj")).string(), "--max-depth", "3"},
        {(kCorpus / "gltf" / "Duck.glb").string(), "--max-depth", "4"},
    };
    for (std::vector<std::string> args : cases) {
        SCOPED_TRACE(args[0]);
        if (!fs::exists(args[0])) {
            ADD_FAILURE() << args[0] << " is missing (LOOPTESS_CORPUS_DIR=" << kCorpus << ")";
            continue;
        }
        const fs::path out = root_ / "out.glb", report = root_ / "out.json";
        args.insert(args.end(), {"-o", out.string(), "--json", report.string()});
        Bytes glb[2];
        std::string json[2];
        for (int i = 0; i < 2; ++i) {
            const RunResult r = loopbake(args, root_);
            ASSERT_EQ(r.exitCode, 0) << r.err;
            glb[i] = readBytes(out);
            json[i] = readText(report);
            fs::remove(out);
            fs::remove(report);
        }
        EXPECT_FALSE(glb[0].empty());
        EXPECT_TRUE(glb[0] == glb[1]) << describeDifference(glb[0], glb[1]);
        EXPECT_FALSE(Json::parse(json[0], nullptr, false).is_discarded()) << json[0];
        EXPECT_EQ(json[0], json[1]);
    }
}

// --json is written whatever the outcome, so that a build system reading it learns
// why a bake failed instead of finding no file: "status", "exitCode" and "message"
// (as a manifest's jobs have them), and no output file. Before, a failed single bake
// wrote no report.
TEST_F(BakeFiles, TheJsonReportSaysWhetherTheBakeFailed) {
    const fs::path bad = root_ / "bad.obj", out = root_ / "out.glb", report = root_ / "report.json";
    const std::string text = "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
    ASSERT_TRUE(writeBytes(bad, Bytes(text.begin(), text.end())));
    RunResult r = loopbake({bad.string(), "-o", out.string(), "--json", report.string()}, root_);
    ASSERT_EQ(r.exitCode, 2) << r.err;
    EXPECT_FALSE(fs::exists(out));
    ASSERT_TRUE(fs::exists(report)) << "no report after a failed bake";
    Json j = Json::parse(readText(report), nullptr, false);
    ASSERT_FALSE(j.is_discarded());
    EXPECT_EQ(j["status"], "failed");
    EXPECT_EQ(j["exitCode"], 2);
    EXPECT_NE(j["message"].get<std::string>().find("bad.obj"), std::string::npos) << j["message"];
    EXPECT_NE(r.err.find(j["message"].get<std::string>()), std::string::npos) << "the message stderr gives";
    EXPECT_EQ(j["input"]["file"], bad.string());
    r = loopbake(
        {(kData / (kGoldenShape + ".obj")).string(), "-o", out.string(), "--max-depth", "1", "--json", report.string()},
        root_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    j = Json::parse(readText(report), nullptr, false);
    EXPECT_EQ(j["status"], "ok");
    EXPECT_EQ(j["exitCode"], 0);
}

// A report or depfile naming the input, the output or each other is a usage error
// before anything is read or written (before: exit 0, the input or the GLB replaced
// by the report's text).
TEST_F(BakeFiles, AReportNeverOverwritesTheInputOrTheOutput) {
    const fs::path source = root_ / "a.obj", out = root_ / "a.glb";
    fs::copy_file(kData / (kGoldenShape + ".obj"), source);
    const Bytes original = readBytes(source);
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--depfile", source.string()}, "--depfile '" + source.string() + "' is also the input"},
        {{"--json", (root_ / "." / "a.obj").string()}, "is also the input"},
        {{"--depfile", out.string()}, "is also -o"},
        {{"--json", (root_ / "r.json").string(), "--depfile", (root_ / "r.json").string()}, "is also --json"},
    };
    for (const auto& [options, expected] : cases) {
        std::vector<std::string> args = {source.string(), "-o", out.string()};
        args.insert(args.end(), options.begin(), options.end());
        const RunResult r = loopbake(args, root_);
        SCOPED_TRACE(options[1]);
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
        EXPECT_TRUE(readBytes(source) == original);
        EXPECT_FALSE(fs::exists(out));
    }
}

// ---- 3 + 4. Khronos glTF-Validator and round trips on baked files ----------------------

// The issue's "done when": every corpus shape either bakes (and the file passes the
// Khronos glTF-Validator with 0 errors and 0 warnings and round-trips through
// readAssetGlb/writeAssetGlb) or is rejected with exit 2 and a message naming it.
TEST_F(BakeFiles, CorpusBakesOrFailsClearly) {
    ASSERT_NO_FATAL_FAILURE(requireValidator());
    const std::vector<fs::path> shapes = corpusShapes();
    ASSERT_FALSE(shapes.empty()) << "no OpenSubdiv shapes under " << kCorpus / "opensubdiv-loop"
                                 << " (set LOOPTESS_CORPUS_DIR)";
    std::vector<std::string> baked, rejected;
    for (const fs::path& obj : shapes) {
        SCOPED_TRACE(obj.string());
        const fs::path out = root_ / (obj.stem().string() + ".glb");
        const RunResult r = loopbake({obj.string(), "-o", out.string()}, root_);
        if (r.exitCode != 0) {
            rejected.push_back(obj.stem().string());
            EXPECT_EQ(r.exitCode, 2) << "a rejected shape must exit 2 (bad input):\n" << r.err;
            const std::string prefix = "loopbake: error: " + obj.string() + ": ";
            const size_t at = r.err.find(prefix);
            ASSERT_NE(at, std::string::npos) << "stderr must say what is wrong:\n" << r.err;
            const std::string why = r.err.substr(at + prefix.size(), r.err.find('\n', at) - at - prefix.size());
            EXPECT_GE(why.size(), 10u) << "message too vague: " << r.err;
            EXPECT_FALSE(fs::exists(out)) << "no output may be left after a failure";
            std::cout << "rejected " << obj.filename().string() << ": " << why << "\n";
            continue;
        }
        baked.push_back(obj.stem().string());
        const Bytes bytes = readBytes(out);
        ASSERT_FALSE(bytes.empty());
        expectKhronosValid(out, root_);
        expectRoundTrip(bytes, out.filename().string());
        fs::remove(out);
    }
    std::cout << shapes.size() << " corpus shapes: " << baked.size() << " baked (Khronos-valid, "
              << "round-trip exact), " << rejected.size() << " rejected with exit 2\n";
    RecordProperty("baked", int(baked.size()));
    RecordProperty("rejected", int(rejected.size()));
    EXPECT_GT(baked.size(), rejected.size()) << "most OpenSubdiv shapes must bake";
}

// Larger real meshes: spot (UVs, 5,856 triangles) at --max-depth 4 and the Khronos
// Duck (.glb input) at the default depth.
TEST_F(BakeFiles, SpotAndDuckPassTheKhronosValidator) {
    ASSERT_NO_FATAL_FAILURE(requireValidator());
    const std::vector<std::vector<std::string>> cases = {
        {(kCorpus / "meshes" / "spot.obj").string(), "--max-depth", "4"},
        {(kCorpus / "gltf" / "Duck.glb").string()},
    };
    for (std::vector<std::string> args : cases) {
        SCOPED_TRACE(args[0]);
        ASSERT_TRUE(fs::exists(args[0])) << "missing (LOOPTESS_CORPUS_DIR=" << kCorpus << ")";
        const fs::path out = root_ / (fs::path(args[0]).stem().string() + ".glb");
        args.insert(args.end(), {"-o", out.string()});
        const RunResult r = loopbake(args, root_);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Bytes bytes = readBytes(out);
        ASSERT_FALSE(bytes.empty());
        expectKhronosValid(out, root_);
        if (fs::path(args[0]).extension() == ".obj") expectRoundTrip(bytes, out.filename().string());
        fs::remove(out);
    }
}

// --compress none|fast|max: the same tables (read back and written plain, the bytes
// agree), files that shrink in that order, each valid glTF, and reports whose
// encoded bytes say what the file holds.
TEST_F(BakeFiles, CompressSettingsStoreTheSameTables) {
    ASSERT_NO_FATAL_FAILURE(requireValidator());
    const fs::path spot = kCorpus / "meshes" / "spot.obj";
    ASSERT_TRUE(fs::exists(spot)) << "missing (LOOPTESS_CORPUS_DIR=" << kCorpus << ")";
    Bytes plainTables;
    size_t previous = SIZE_MAX;
    for (const char* setting : {"none", "fast", "max"}) {
        SCOPED_TRACE(setting);
        const fs::path out = root_ / (std::string(setting) + ".glb"), report = root_ / "report.json";
        const RunResult r = loopbake(
            {spot.string(), "-o", out.string(), "--max-depth", "4", "--compress", setting, "--json", report.string()},
            root_);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const Bytes bytes = readBytes(out);
        expectKhronosValid(out, root_);
        lt::Asset asset;
        const lt::Status st = lt::readAssetGlb(bytes.data(), bytes.size(), out.string(), asset);
        ASSERT_TRUE(st) << st.message;
        Bytes rewritten;
        ASSERT_TRUE(lt::writeAssetGlb(asset, rewritten, nullptr, lt::Compression::None));
        if (plainTables.empty()) plainTables = rewritten;
        EXPECT_TRUE(rewritten == plainTables) << describeDifference(plainTables, rewritten);
        EXPECT_LT(bytes.size(), previous);
        previous = bytes.size();

        const Json j = Json::parse(readText(report));
        EXPECT_EQ(j["settings"]["compress"], setting);
        EXPECT_EQ(j["output"]["bytes"].get<size_t>(), bytes.size());
        const size_t raw = j["tableBytes"]["total"], encoded = j["encodedBytes"]["total"];
        if (std::string(setting) == "none")
            EXPECT_EQ(encoded, raw);
        else
            EXPECT_LT(encoded, raw / 2);
        EXPECT_LE(encoded, bytes.size());
    }
    const RunResult bad = loopbake({spot.string(), "-o", (root_ / "x.glb").string(), "--compress", "zip"}, root_);
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find("--compress must be none, fast or max"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(root_ / "x.glb"));
}

}  // namespace
