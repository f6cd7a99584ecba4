// lt::bake and lt::writeAssetGlb on several threads: the same bytes for every
// count (BakeSettings::threads), on spot (smooth, 645 extraordinary vertices) and
// on corpus meshes with creases -- fandisk with its feature edges made sharp by
// angle (crease and corner stencils, oriented), and semi-sharp cubes (stencils of
// vertices whose rule changes with the level).
#include "looptess/tools/baker.h"
#include "tool_run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using Bytes = std::vector<uint8_t>;

const fs::path kData = LOOPTESS_TEST_DATA;
const fs::path kCorpus = LOOPTESS_CORPUS_DIR;

// Reads `obj`, adds creases at dihedral angles above `creaseAngle` (when > 0), bakes
// at depth 6 on `threads` threads and writes the default GLB on as many.
lt::Status bakeObj(const fs::path& obj, float creaseAngle, unsigned threads, Bytes& bytes) {
    lt::InputMesh mesh;
    lt::Status st = lt::parseObj(lt::test::readText(obj), obj.string(), lt::InputOptions{}, mesh);
    if (st) st = lt::checkInput(mesh, obj.string());
    if (st && creaseAngle > 0) lt::addCreasesByAngle(mesh, creaseAngle);
    lt::Asset asset;
    lt::BakeSettings settings;
    settings.maxDepth = 6;
    settings.threads = threads;
    if (st) st = lt::bake(mesh, settings, asset);
    if (st) st = lt::writeAssetGlb(asset, bytes, nullptr, lt::Compression::Fast, threads);
    return st;
}

void expectSameBytes(const fs::path& obj, float creaseAngle) {
    ASSERT_TRUE(fs::exists(obj)) << obj << " is missing";
    Bytes serial;
    const lt::Status st = bakeObj(obj, creaseAngle, 1, serial);
    ASSERT_TRUE(st) << st.message;
    for (unsigned threads : {2u, 3u, 8u}) {
        SCOPED_TRACE(obj.filename().string() + " on " + std::to_string(threads) + " threads");
        Bytes bytes;
        const lt::Status s = bakeObj(obj, creaseAngle, threads, bytes);
        ASSERT_TRUE(s) << s.message;
        EXPECT_EQ(bytes.size(), serial.size());
        EXPECT_TRUE(bytes == serial) << "the GLB differs from the one baked on 1 thread";
    }
}

TEST(BakeThreads, SpotSameBytesForEveryCount) { expectSameBytes(kData / "spot.obj", 0); }

TEST(BakeThreads, CreasedCorpusMeshesSameBytesForEveryCount) {
    expectSameBytes(kCorpus / "meshes" / "fandisk.obj", 40);
    expectSameBytes(kCorpus / "opensubdiv-loop" / "loop_cubes_semisharp.obj", 0);
}

}  // namespace
