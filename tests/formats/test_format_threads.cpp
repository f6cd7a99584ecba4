// tests/formats/test_format_threads.cpp -- the reader's level tables are decoded and
// checked on several threads (formats/internal/reader.h): a baked asset reads back
// the same, and a file broken in two levels gets the same message, whatever the
// thread count.
#include "format_fixture.h"
#include "reader.h"

#include "looptess/tools/baker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace {

using namespace fmttest;

constexpr size_t kThreadCounts[] = {1, 2, 3, 8};

// An n x n torus grid, every seventh cell's diagonal flipped (valence 5 and 7
// vertices), baked to depth 4: several levels of every kind of table.
lt::Asset bakedTorus() {
    const uint32_t n = 16;
    lt::InputMesh mesh;
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j) {
            const float u = 6.2831853f * float(i) / float(n), v = 6.2831853f * float(j) / float(n);
            const float r = 1.0f + 0.35f * std::cos(v);
            mesh.positions.insert(mesh.positions.end(), {r * std::cos(u), r * std::sin(u), 0.35f * std::sin(v)});
        }
    auto at = [&](uint32_t i, uint32_t j) { return (i % n) * n + j % n; };
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if ((i * n + j) % 7 == 0)
                mesh.faces.insert(mesh.faces.end(), {a, b, d, b, c, d});
            else
                mesh.faces.insert(mesh.faces.end(), {a, b, c, a, c, d});
        }
    lt::BakeSettings settings;
    settings.maxDepth = 4;
    lt::Asset asset;
    const lt::Status st = lt::bake(mesh, settings, asset);
    EXPECT_TRUE(st) << st.message;
    return asset;
}

lt::Status readWith(const std::vector<uint8_t>& bytes, size_t threads, lt::Asset& out) {
    std::vector<lt::SceneSurface> surfaces;
    lt::Status st = lt::fmt::readSceneGlb(bytes.data(), bytes.size(), "t.glb", surfaces, threads);
    if (st) out = std::move(surfaces[0].asset);
    return st;
}

TEST(ReaderThreads, EveryThreadCountReadsTheSameAsset) {
    const lt::Asset a = bakedTorus();
    ASSERT_GE(a.levels.size(), 3u);
    for (lt::Compression c : {lt::Compression::None, lt::Compression::Fast}) {
        const std::vector<uint8_t> bytes = write(a, nullptr, c);
        for (size_t threads : kThreadCounts) {
            SCOPED_TRACE("compression " + std::to_string(int(c)) + ", " + std::to_string(threads) + " threads");
            lt::Asset b;
            const lt::Status st = readWith(bytes, threads, b);
            ASSERT_TRUE(st) << st.message;
            expectEqual(a, b);
        }
    }
}

// Level 1 breaks rule 25 (a vertex parent outside level 0) and level 2 rules 15
// and 30: a serial read stops at the first, so every thread count must name it.
TEST(ReaderThreads, TheFirstBrokenLevelIsNamedWhateverTheThreadCount) {
    Glb g(fixtureBytes());
    g.setIndex(g.accessor(1, "vertexParent"), 0, 9999);
    g.setIndex(g.accessor(2, "regularPoints"), 0, 9999);
    const std::vector<uint8_t> refinementAndPatch = g.bytes();
    g.ext()["levels"][2].erase("regularBaseFace");  // rule 15, found before any level decodes
    const std::vector<uint8_t> countsToo = g.bytes();
    for (const auto& [bytes, expected] : {std::pair{&refinementAndPatch, "levels[1].vertexParent[0]: rule 25: "},
                                          std::pair{&countsToo, "levels[2].regularBaseFace: rule 15: "}}) {
        std::string first;
        for (size_t threads : kThreadCounts) {
            SCOPED_TRACE(std::to_string(threads) + " threads");
            lt::Asset b;
            const lt::Status st = readWith(*bytes, threads, b);
            ASSERT_FALSE(st);
            EXPECT_NE(st.message.find(expected), std::string::npos) << st.message;
            if (first.empty()) first = st.message;
            EXPECT_EQ(st.message, first);
        }
    }
}

}  // namespace
