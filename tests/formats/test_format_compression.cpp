// tests/formats/test_format_compression.cpp -- compressed table streams (spec "Compression",
// rule 46): every setting round-trips bit for bit, the stream holds exactly the
// surface's table accessors, sizes add up, output is deterministic (the Khronos
// validator's tests are in test_format.cpp), a stream that would break rule 46's
// ratio is written plain, and broken streams are rejected citing rule 46 (or the rule
// of the glTF object that is wrong) without crashing.
#include "format_fixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <zstd.h>

#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace {

using namespace fmttest;

constexpr lt::Compression kAll[] = {lt::Compression::None, lt::Compression::Fast, lt::Compression::Max};

// The accessors a surface object and its cage object name.
std::set<int> tableAccessors(Glb& g) {
    std::set<int> out;
    for (const Json& level : g.ext()["levels"])
        for (auto it = level.begin(); it != level.end(); ++it)
            if (it.key() != "firstVertex") out.insert(it->get<int>());
    if (g.ext().contains("editValues")) out.insert(g.ext()["editValues"].get<int>());
    if (g.ext().contains("displacement"))
        for (const char* k : {"faceEdges", "values"}) out.insert(g.ext()["displacement"][k].get<int>());
    if (g.cage().contains("controlVertex")) out.insert(g.cage()["controlVertex"].get<int>());
    return out;
}

// Every table accessor on a bufferView of its own, no stream, each kind's bytes in
// the file its own bytes.
void expectPlainTables(Glb& g, const lt::TableBytes& tb) {
    EXPECT_FALSE(g.ext().contains("compression"));
    for (int acc : tableAccessors(g)) EXPECT_TRUE(g.doc["accessors"][acc].contains("bufferView"));
    EXPECT_EQ(tb.encoded.total(), tb.total());
}

TEST(Compression, EverySettingRoundTripsBitForBit) {
    const lt::Asset assets[] = {makeAsset(true), makeAsset(false), makeBigAsset()};
    const lt::Asset& big = assets[2];
    for (const lt::Asset& a : assets) {
        size_t previous = SIZE_MAX;
        for (lt::Compression c : kAll) {
            SCOPED_TRACE("compression " + std::to_string(int(c)) + ", " + std::to_string(a.controlVertexCount()) +
                         " control vertices");
            lt::TableBytes tb;
            const std::vector<uint8_t> bytes = write(a, &tb, c);
            lt::Asset b;
            const lt::Status st = read(bytes, &b);
            ASSERT_TRUE(st) << st.message;
            expectEqual(a, b);
            EXPECT_EQ(write(b, nullptr, c), bytes);  // deterministic
            Glb g(bytes);
            const std::set<int> tables = tableAccessors(g);
            // The big asset's tables are mostly its 70,000-entry controlVertex map, which
            // Zstandard may take to more than rule 46's 256 to 1: then they are plain.
            if (c == lt::Compression::None || (&a == &big && !g.ext().contains("compression"))) {
                expectPlainTables(g, tb);
            } else {
                // The stream lists exactly the table accessors, none of which has a bufferView.
                ASSERT_TRUE(g.ext().contains("compression"));
                const Json& z = g.ext()["compression"];
                EXPECT_EQ(z["method"], "BYTE_PLANES_ZSTD");
                std::set<int> listed;
                for (const Json& i : z["accessors"]) listed.insert(i.get<int>());
                EXPECT_EQ(listed, tables);
                for (int acc : tables) EXPECT_FALSE(g.doc["accessors"][acc].contains("bufferView"));
                const size_t streamBytes = g.doc["bufferViews"][z["bufferView"].get<int>()]["byteLength"];
                EXPECT_LE(streamBytes, tb.encoded.total());
                EXPECT_LE(bytes.size(), previous);  // none >= fast >= max, on these small assets too
            }
            previous = bytes.size();
        }
    }
}

// Rule 46 bounds a stream's decoded bytes by 256 times its own: a surface whose
// tables compress further (here 800 KB of an increasing map, to about 1 KB) has them
// written plain at every setting, and reads back.
TEST(Compression, AStreamPastRule46sRatioIsWrittenPlain) {
    const lt::Asset a = makeAsset(true, 200000);
    for (lt::Compression c : kAll) {
        SCOPED_TRACE("compression " + std::to_string(int(c)));
        lt::TableBytes tb;
        const std::vector<uint8_t> bytes = write(a, &tb, c);
        Glb g(bytes);
        expectPlainTables(g, tb);
        lt::Asset b;
        const lt::Status st = read(bytes, &b);
        ASSERT_TRUE(st) << st.message;
        expectEqual(a, b);
    }
}

TEST(Compression, EncodedBytesAddUpToTheFile) {
    const lt::Asset a = makeBigAsset();
    lt::TableBytes plain, fast;
    const std::vector<uint8_t> none = write(a, &plain, lt::Compression::None);
    const std::vector<uint8_t> packed = write(a, &fast, lt::Compression::Fast);
    // Raw sizes do not depend on the setting; what the file holds does.
    EXPECT_EQ(plain.total(), fast.total());
    EXPECT_EQ(plain.patches, fast.patches);
    Glb g(packed);
    const Json& z = g.ext()["compression"];
    const size_t streamBytes = g.doc["bufferViews"][z["bufferView"].get<int>()]["byteLength"];
    // Encoded = the stream, split by kind, plus the fallback primitive's plain accessors.
    size_t fallback = 0;
    for (const Json& v : g.doc["bufferViews"]) fallback += v["byteLength"].get<size_t>();
    fallback -= streamBytes;
    EXPECT_EQ(fast.encoded.total(), streamBytes + fallback);
    EXPECT_LT(fast.encoded.patches, fast.patches);
    // The tables shrink; the fallback primitive (most of this file) does not.
    const size_t raw = fast.total() - fast.controlMesh, encoded = fast.encoded.total() - fast.encoded.controlMesh;
    EXPECT_LT(encoded, raw);
    EXPECT_LT(packed.size(), none.size());
}

// --- rule 46 and its neighbours ------------------------------------------------------------

const std::vector<uint8_t>& compressedBytes() {
    static const std::vector<uint8_t> bytes = write(makeAsset(true), nullptr, lt::Compression::Fast);
    return bytes;
}

void corruptStream(const std::function<void(Glb&)>& edit, int rule) {
    Glb g(compressedBytes());
    edit(g);
    expectRule(read(g.bytes()), rule);
}

Json& stream(Glb& g) { return g.ext()["compression"]; }
Json& streamView(Glb& g) { return g.doc["bufferViews"][stream(g)["bufferView"].get<int>()]; }
size_t streamAt(Glb& g) { return streamView(g).value("byteOffset", size_t(0)); }
int listed(Glb& g, size_t i) { return stream(g)["accessors"][i].get<int>(); }

TEST(Corrupt, CompressionObject) {
    corruptStream([](Edit g) { stream(g)["method"] = "MESHOPT"; }, 46);
    corruptStream([](Edit g) { stream(g) = Json::array(); }, 46);
    corruptStream([](Edit g) { stream(g)["bufferView"] = 999; }, 46);
    corruptStream([](Edit g) { stream(g)["accessors"] = Json::array(); }, 46);
    corruptStream([](Edit g) { stream(g)["accessors"][0] = -1; }, 46);
    corruptStream([](Edit g) { streamView(g)["byteStride"] = 4; }, 46);
    corruptStream([](Edit g) { streamView(g)["byteLength"] = g.bin.size() + 4; }, 5);
}

TEST(Corrupt, CompressionAccessorList) {
    corruptStream([](Edit g) { stream(g)["accessors"].push_back(listed(g, 0)); }, 46);  // twice
    corruptStream([](Edit g) { g.doc["accessors"][listed(g, 1)]["bufferView"] = 0; }, 46);
    corruptStream([](Edit g) { g.doc["accessors"][listed(g, 1)]["byteOffset"] = 4; }, 46);
    // A table accessor without bufferView that no stream lists: rule 6.
    corruptStream([](Edit g) { stream(g)["accessors"].erase(stream(g)["accessors"].size() - 1); }, 6);
    // A listed accessor that the surface does not name.
    corruptStream(
        [](Edit g) {
            Json extra = g.doc["accessors"][listed(g, 0)];
            g.doc["accessors"].push_back(extra);
            stream(g)["accessors"].push_back(g.doc["accessors"].size() - 1);
        },
        46);
    // The cage is never compressed (its reader would read another surface's stream).
    corruptStream([](Edit g) { prim(g)["indices"] = g.ext()["levels"][1]["vertexParent"]; }, 46);
    // Sizes: the frame declares what the list needs, and no more than 256x its bytes.
    corruptStream(
        [](Edit g) {
            Json& a = g.doc["accessors"][listed(g, 1)];
            a["count"] = a["count"].get<uint64_t>() + 1;
        },
        46);
    corruptStream([](Edit g) { g.doc["accessors"][listed(g, 1)]["count"] = uint64_t(1) << 40; }, 46);
}

TEST(Corrupt, CompressionFrame) {
    corruptStream([](Edit g) { g.bin[streamAt(g)] ^= 0xFF; }, 46);  // magic
    corruptStream([](Edit g) { streamView(g)["byteLength"] = streamView(g)["byteLength"].get<size_t>() - 3; }, 46);
    corruptStream(
        [](Edit g) {  // a byte after the frame
            Json& v = streamView(g);
            if (streamAt(g) + v["byteLength"].get<size_t>() == g.bin.size()) {
                g.bin.resize(g.bin.size() + 4, 0);
                g.doc["buffers"][0]["byteLength"] = g.bin.size();
            }
            v["byteLength"] = v["byteLength"].get<size_t>() + 1;
        },
        46);
}

// The stream as Zstandard frames cut at `cuts` (decoded bytes, increasing), in
// place of the writer's one frame: appended to the BIN chunk, the stream's view
// pointing at it. `extra` is appended after the last frame.
void reframe(Glb& g, const std::vector<size_t>& cuts, const std::vector<uint8_t>& extra = {}) {
    const uint8_t* frame = g.bin.data() + streamAt(g);
    const size_t length = streamView(g)["byteLength"].get<size_t>();
    std::vector<uint8_t> decoded(ZSTD_getFrameContentSize(frame, length));
    ASSERT_EQ(ZSTD_decompress(decoded.data(), decoded.size(), frame, length), decoded.size());
    std::vector<uint8_t> frames;
    size_t from = 0;
    for (size_t to : cuts) {
        std::vector<uint8_t> one(ZSTD_compressBound(to - from));
        const size_t n = ZSTD_compress(one.data(), one.size(), decoded.data() + from, to - from, 3);
        ASSERT_FALSE(ZSTD_isError(n));
        frames.insert(frames.end(), one.begin(), one.begin() + n);
        from = to;
    }
    frames.insert(frames.end(), extra.begin(), extra.end());
    g.bin.resize((g.bin.size() + 3) / 4 * 4);
    streamView(g)["byteOffset"] = g.bin.size();
    streamView(g)["byteLength"] = frames.size();
    g.bin.insert(g.bin.end(), frames.begin(), frames.end());
    g.bin.resize((g.bin.size() + 3) / 4 * 4);
    g.doc["buffers"][0]["byteLength"] = g.bin.size();
}

size_t decodedBytes(Glb& g) {
    return ZSTD_getFrameContentSize(g.bin.data() + streamAt(g), streamView(g)["byteLength"]);
}

// A stream may be several frames back to back (the writer cuts one per 8 MiB of
// planes, so that readers can decode them in parallel), cut anywhere: inside a
// segment, inside a plane. The tables read back the same.
TEST(Compression, FramesCutAnywhereReadTheSame) {
    lt::Asset expected;
    ASSERT_TRUE(read(compressedBytes(), &expected));
    Glb g(compressedBytes());
    const size_t d = decodedBytes(g);
    ASSERT_GT(d, 100u);
    reframe(g, {1, d / 3, d / 3 + 7, d - 1, d});  // 1-byte frames, an odd cut, an empty-free end
    lt::Asset back;
    ASSERT_TRUE(read(g.bytes(), &back));
    EXPECT_EQ(back.levels.size(), expected.levels.size());
    EXPECT_EQ(back.totalVertexCount(), expected.totalVertexCount());
    EXPECT_EQ(write(back, nullptr, lt::Compression::None), write(expected, nullptr, lt::Compression::None));
}

TEST(Corrupt, CompressionFrames) {
    auto framed = [](const std::function<void(Glb&, size_t)>& edit) {
        Glb g(compressedBytes());
        edit(g, decodedBytes(g));
        const lt::Status st = read(g.bytes());
        expectRule(st, 46);
        return st.message;
    };
    // The frames declare less, or more, than the accessors need.
    EXPECT_NE(framed([](Glb& g, size_t d) { reframe(g, {d / 2}); }).find("frames declare"), std::string::npos);
    EXPECT_NE(framed([](Glb& g, size_t d) {
                  std::vector<uint8_t> more(ZSTD_compressBound(8));
                  const uint8_t eight[8] = {};
                  more.resize(ZSTD_compress(more.data(), more.size(), eight, 8, 1));
                  reframe(g, {d}, more);
              }).find("more than"),
              std::string::npos);
    // A second frame that is not one, names it.
    EXPECT_NE(framed([](Glb& g, size_t d) {
                  reframe(g, {d / 2, d}, {1, 2, 3, 4});
              }).find("frame 2"),
              std::string::npos);
    // A truncated second frame, named.
    EXPECT_NE(framed([](Glb& g, size_t d) {
                  reframe(g, {d / 2, d});
                  streamView(g)["byteLength"] = streamView(g)["byteLength"].get<size_t>() - 2;
              }).find("frame 1 is truncated"),
              std::string::npos);
}

// Flipping any byte of the stream never crashes the reader: it is rejected, or it
// decodes to tables that the validator then judges (zstd checks its structure, not
// the literal bytes). Under the sanitizers this is the stream's memory-safety test.
TEST(Compression, EveryFlippedByteIsSafe) {
    Glb g(compressedBytes());
    const size_t at = streamAt(g), length = streamView(g)["byteLength"].get<size_t>();
    std::mt19937 rng(46);
    size_t rejected = 0;
    for (size_t i = 0; i < length; ++i) {
        Glb h = g;
        h.bin[at + i] ^= uint8_t(1u << (rng() % 8));
        lt::Asset out;
        if (!read(h.bytes(), &out)) ++rejected;
    }
    EXPECT_GT(rejected, 0u);
}

}  // namespace
