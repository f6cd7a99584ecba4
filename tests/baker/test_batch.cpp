// test_batch.cpp -- loopbake --manifest (apps/loopbake/batch.h): the same bytes with any
// thread count, a failed job neither stops the others nor leaves a file, malformed
// manifests bake nothing; and a write failing half-way leaves no partial file.
#include "looptess/tools/baker.h"

#include "tool_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;
using Json = nlohmann::json;
using lt::test::readText;
using lt::test::RunResult;

namespace {

const fs::path kData = LOOPTESS_TEST_DATA;
const fs::path kCorpus = LOOPTESS_CORPUS_DIR;

using lt::test::contains;

std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

class Batch : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("looptess_test_batch_" + std::to_string(getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "out");
    }
    void TearDown() override { fs::remove_all(dir_); }

    RunResult loopbake(const std::vector<std::string>& args) { return lt::test::runTool(LOOPBAKE_EXE, args, dir_); }
    void writeManifest(const Json& j, const std::string& name = "list.json") {
        std::ofstream(dir_ / name) << j.dump(2);
    }

    fs::path dir_;
};

// Four small corpus meshes (three OBJ with tags, one glTF), with per-job options.
Json fourJobs() {
    return {{"jobs",
             {{{"input", (kData / "loop_icos_semisharp.obj").string()}, {"output", "out/icos.glb"}, {"max-depth", 4}},
              {{"input", (kCorpus / "opensubdiv-loop" / "loop_cube_creases0.obj").string()},
               {"output", "out/cube.glb"},
               {"crease-angle", 30}},
              {{"input", (kCorpus / "opensubdiv-loop" / "loop_pole64.obj").string()}, {"output", "out/pole.glb"}},
              {{"input", (kCorpus / "gltf" / "Duck.glb").string()}, {"output", "out/duck.glb"}, {"max-depth", "3"}}}}};
}

TEST_F(Batch, ThreadCountDoesNotChangeTheBytes) {
    writeManifest(fourJobs());
    const std::vector<std::string> names = {"cube.glb", "duck.glb", "icos.glb", "pole.glb"};
    std::vector<std::string> glb[2];
    std::string report[2];
    for (int run = 0; run < 2; ++run) {
        const std::string threads = run == 0 ? "1" : "3";
        SCOPED_TRACE("--threads " + threads);
        const RunResult r = loopbake({"--manifest", (dir_ / "list.json").string(), "--threads", threads, "--json",
                                      (dir_ / "report.json").string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        ASSERT_EQ(entries(dir_ / "out"), names);
        for (const std::string& n : names) glb[run].push_back(readText(dir_ / "out" / n));
        report[run] = readText(dir_ / "report.json");
        fs::remove_all(dir_ / "out");
        fs::create_directories(dir_ / "out");
    }
    for (size_t i = 0; i < names.size(); ++i) {
        EXPECT_FALSE(glb[0][i].empty()) << names[i];
        EXPECT_TRUE(glb[0][i] == glb[1][i]) << names[i] << " differs between --threads 1 and 3";
    }
    EXPECT_EQ(report[0], report[1]) << "the report (without -v) is byte-stable across thread counts";
    const Json j = Json::parse(report[0]);
    EXPECT_EQ(j["summary"]["succeeded"], 4);
    EXPECT_EQ(j["jobs"][0]["report"]["settings"]["maxDepth"], 4);
    EXPECT_EQ(j["jobs"][3]["report"]["settings"]["maxDepth"], 3);
    EXPECT_EQ(j["jobs"][1]["bytes"].get<size_t>(), glb[0][0].size()) << "cube.glb";

    // A job bakes the same bytes as the same options given to a single bake.
    const fs::path single = dir_ / "single.glb";
    const RunResult r =
        loopbake({(kData / "loop_icos_semisharp.obj").string(), "-o", single.string(), "--max-depth", "4"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(readText(single) == glb[0][2]) << "manifest job vs single bake";
}

TEST_F(Batch, AFailedJobStopsNothingAndLeavesNoFile) {
    Json j = fourJobs();
    // Jobs 1 and 3 fail: a flipped face (bad input) and a face limit; job 4 cannot write.
    j["jobs"][1]["input"] = (kData / "bad" / "flipped_face.obj").string();
    j["jobs"][3]["max-faces"] = 100;
    j["jobs"].push_back({{"input", (kData / "loop_icos_semisharp.obj").string()},
                         {"output", "missing_dir/icos.glb"},
                         {"max-depth", 2}});
    writeManifest(j);
    for (const char* threads : {"1", "2"}) {
        SCOPED_TRACE(std::string("--threads ") + threads);
        const fs::path report = dir_ / "report.json";
        const RunResult r = loopbake(
            {"--manifest", (dir_ / "list.json").string(), "--json", report.string(), "--threads", threads, "-v"});
        EXPECT_EQ(r.exitCode, 2) << "the first failed job's exit code (bad input)\n" << r.err;
        EXPECT_EQ(entries(dir_ / "out"), (std::vector<std::string>{"icos.glb", "pole.glb"}))
            << "the jobs after a failure still run; a failed job leaves no file, not even a temporary";
        EXPECT_FALSE(fs::exists(dir_ / "missing_dir"));
        EXPECT_TRUE(contains(r.err, "flipped_face.obj")) << r.err;
        EXPECT_TRUE(contains(r.err, "2 of 5 jobs succeeded, 3 failed")) << r.err;
        const Json rep = Json::parse(readText(report));
        const std::vector<std::string> status = {"ok", "failed", "ok", "failed", "failed"};
        const std::vector<int> codes = {0, 2, 0, 2, 4};
        for (size_t i = 0; i < status.size(); ++i) {
            EXPECT_EQ(rep["jobs"][i]["status"], status[i]) << i;
            EXPECT_EQ(rep["jobs"][i]["exitCode"], codes[i]) << i;
            EXPECT_EQ(rep["jobs"][i]["bytes"].get<uint64_t>() > 0, status[i] == "ok") << i;
            EXPECT_TRUE(rep["jobs"][i].contains("seconds")) << "timings with -v";
        }
        EXPECT_TRUE(contains(rep["jobs"][3]["message"], "--max-faces")) << rep["jobs"][3]["message"];
        EXPECT_TRUE(contains(rep["jobs"][4]["message"], "cannot create")) << rep["jobs"][4]["message"];
        EXPECT_EQ(rep["summary"]["failed"], 3);
        fs::remove_all(dir_ / "out");
        fs::create_directories(dir_ / "out");
    }
}

TEST_F(Batch, MalformedManifestsBakeNothing) {
    const std::string icos = (kData / "loop_icos_semisharp.obj").string();
    const Json ok = {{"input", icos}, {"output", "out/a.glb"}};
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"{\"jobs\": [", "list.json: is not valid JSON"},
        {R"([{"input": "a.obj"}])", "the top level must be an object"},
        {R"({"job": []})", "list.json: job: unknown key"},
        {Json{{"jobs", {ok, {{"input", icos}}}}}.dump(), "jobs[1].output: missing"},
        {Json{{"jobs", {ok, {{"input", icos}, {"output", "out/b.glb"}, {"max-dept", 3}}}}}.dump(),
         "jobs[1] (" + icos + "): unknown option '--max-dept=3'"},
        {Json{{"jobs", {ok, {{"input", icos}, {"output", "out/b.glb"}, {"max-depth", 12}}}}}.dump(),
         "--max-depth must be an integer from 1 to 8"},
        {Json{{"jobs", {ok, {{"input", icos}, {"output", "out/b.glb"}, {"threads", 2}}}}}.dump(),
         "jobs[1].threads: a batch-wide option"},
        {Json{{"jobs", {ok, {{"input", icos}, {"output", "out/b.glb"}, {"max-depth", {1, 2}}}}}}.dump(),
         "jobs[1].max-depth: must be a number, string or boolean"},
        {Json{{"jobs", {ok, {{"input", icos}, {"output", "out/./a.glb"}}}}}.dump(),
         "a.glb\" is also written by jobs[0]"},
        {Json{{"jobs", {ok, {{"input", icos}, {"output", icos}}}}}.dump(), "is the input of jobs[0]"},
        // Depfiles too (before: accepted, one overwriting an input or another's file).
        {Json{{"jobs", {ok, {{"input", icos}, {"output", "out/b.glb"}, {"depfile", "out/a.glb"}}}}}.dump(),
         "out/a.glb\" is also written by jobs[0]"},
        {Json{{"jobs", {ok, {{"input", icos}, {"output", "out/b.glb"}, {"depfile", icos}}}}}.dump(),
         "is the input of jobs[0]"},
        {Json{{"jobs",
               {{{"input", icos}, {"output", "out/a.glb"}, {"depfile", "out/a.d"}},
                {{"input", icos}, {"output", "out/b.glb"}, {"depfile", "out/a.d"}}}}}
             .dump(),
         "out/a.d\" is also written by jobs[0]"},
    };
    for (const auto& [text, expected] : cases) {
        SCOPED_TRACE(text);
        std::ofstream(dir_ / "list.json") << text;
        const RunResult r = loopbake({"--manifest", (dir_ / "list.json").string()});
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_TRUE(contains(r.err, expected)) << r.err;
        EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "nothing is baked from a malformed manifest";
    }
    const RunResult both = loopbake({"--manifest", (dir_ / "list.json").string(), icos, "-o", "x.glb"});
    EXPECT_EQ(both.exitCode, 1) << both.err;
    // Without --manifest, --threads is the threads of the one bake; its value is
    // checked alike.
    const RunResult threads = loopbake({icos, "-o", (dir_ / "out" / "x.glb").string(), "--threads", "many"});
    EXPECT_EQ(threads.exitCode, 1) << threads.err;
    EXPECT_TRUE(contains(threads.err, "--threads must be an integer")) << threads.err;
    EXPECT_EQ(loopbake({icos, "-o", (dir_ / "out" / "x.glb").string(), "--threads", "2"}).exitCode, 0);
    const RunResult missing = loopbake({"--manifest", (dir_ / "nope.json").string()});
    EXPECT_EQ(missing.exitCode, 2) << missing.err;
}

// Paths in a manifest are relative to its folder, wherever loopbake runs from.
TEST_F(Batch, PathsAreRelativeToTheManifest) {
    fs::create_directories(dir_ / "assets" / "baked");
    fs::copy_file(kData / "loop_icos_semisharp.obj", dir_ / "assets" / "icos.obj");
    std::ofstream(dir_ / "assets" / "list.json")
        << R"({"jobs": [{"input": "icos.obj", "output": "baked/icos.glb", "max-depth": 2,
                         "depfile": "baked/icos.glb.d"}]})";
    const RunResult r = loopbake({"--manifest", (dir_ / "assets" / "list.json").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(entries(dir_ / "assets" / "baked"), (std::vector<std::string>{"icos.glb", "icos.glb.d"}));
}

// A write that fails half-way (here: the file-size limit of the process, as a full
// disk would) removes its temporary file and keeps what the output held before.
TEST_F(Batch, FailedWriteLeavesNoPartialFile) {
    const fs::path out = dir_ / "out" / "spot.glb";
    std::ofstream(out) << "previous contents";
    const std::string script = "trap '' XFSZ; ulimit -f 64; exec '" + std::string(LOOPBAKE_EXE) + "' '" +
                               (kData / "spot.obj").string() + "' -o '" + out.string() + "' --max-depth 3";
    const RunResult r = lt::test::runTool("/bin/sh", {"-c", script}, dir_);
    EXPECT_EQ(r.exitCode, 4) << r.err;
    EXPECT_TRUE(contains(r.err, "spot.glb: cannot write")) << r.err;
    EXPECT_EQ(entries(dir_ / "out"), std::vector<std::string>{"spot.glb"}) << "the temporary file must be gone";
    EXPECT_EQ(readText(out), "previous contents") << "a failed bake must not touch the existing output";
}

}  // namespace
