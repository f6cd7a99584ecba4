// tests/formats/test_glb.cpp -- the GLB container reader (looptess/glb.h): what each
// layout accepts, every fault named with the file, the chunk and the lengths, and
// any bytes safe (every prefix and every byte changed of a small file).
#include "format_fixture.h"

#include "looptess/glb.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace {

using Bytes = std::vector<uint8_t>;
using lt::GlbLayout;

struct Chunk {
    uint32_t type;
    std::string data;
};

void put(Bytes& b, uint32_t v) {
    for (int k = 0; k < 4; ++k) b.push_back(uint8_t(v >> (8 * k)));
}

// A GLB of `chunks` as given (no padding added), header length = its size.
Bytes glb(const std::vector<Chunk>& chunks) {
    Bytes b;
    put(b, lt::kGlbMagic);
    put(b, lt::kGlbVersion);
    put(b, 0);
    for (const Chunk& c : chunks) {
        put(b, uint32_t(c.data.size()));
        put(b, c.type);
        b.insert(b.end(), c.data.begin(), c.data.end());
    }
    fmttest::putU32(b, 8, uint32_t(b.size()));
    return b;
}

const std::string kJson = "{\"asset\":{\"version\":\"2.0\"}}     ";  // 32 bytes
const std::string kBin = "0123456789ab";                             // 12 bytes
constexpr uint32_t kOther = 0x12345678;                              // a type glTF does not define

Bytes plain() { return glb({{lt::kGlbChunkJson, kJson}, {lt::kGlbChunkBin, kBin}}); }

lt::Status readChunks(const Bytes& b, GlbLayout layout, lt::GlbChunks& out) {
    return lt::readGlb(b.data(), b.size(), "t.glb", layout, out);
}

// Both layouts reject `b` with a message starting "t.glb: " and containing `what`.
void expectFault(const Bytes& b, const std::string& what) {
    for (GlbLayout layout : {GlbLayout::Strict, GlbLayout::Lenient}) {
        lt::GlbChunks out;
        out.bin = b.data();  // must be cleared
        const lt::Status st = readChunks(b, layout, out);
        ASSERT_FALSE(st) << what;
        EXPECT_EQ(st.code, lt::Status::BadInput);
        EXPECT_EQ(st.message.rfind("t.glb: ", 0), 0u) << st.message;
        EXPECT_NE(st.message.find(what), std::string::npos) << st.message;
        EXPECT_TRUE(out.json.empty() && !out.bin && out.binLength == 0);
    }
}

// Strict rejects `b` with `what`; Lenient reads it.
lt::GlbChunks expectLenientOnly(const Bytes& b, const std::string& what) {
    lt::GlbChunks out;
    const lt::Status strict = readChunks(b, GlbLayout::Strict, out);
    EXPECT_FALSE(strict) << what;
    EXPECT_NE(strict.message.find(what), std::string::npos) << strict.message;
    const lt::Status lenient = readChunks(b, GlbLayout::Lenient, out);
    EXPECT_TRUE(lenient) << lenient.message;
    return out;
}

std::string text(const uint8_t* p, size_t n) { return std::string(reinterpret_cast<const char*>(p), n); }

TEST(Glb, ReadsTheJsonAndBinChunks) {
    for (GlbLayout layout : {GlbLayout::Strict, GlbLayout::Lenient}) {
        const Bytes b = plain();
        lt::GlbChunks out;
        ASSERT_TRUE(readChunks(b, layout, out));
        EXPECT_EQ(out.json, kJson);
        EXPECT_EQ(out.json.data(), reinterpret_cast<const char*>(b.data() + 20));  // a view, not a copy
        ASSERT_EQ(out.binLength, kBin.size());
        EXPECT_EQ(text(out.bin, out.binLength), kBin);
    }
    // A file this library writes.
    const Bytes written = fmttest::write(fmttest::makeAsset(true));
    lt::GlbChunks out;
    ASSERT_TRUE(readChunks(written, GlbLayout::Strict, out));
    EXPECT_EQ(20 + out.json.size() + 8 + out.binLength, written.size());
    EXPECT_TRUE(lt::isGlb(written.data(), written.size()));
}

TEST(Glb, BinIsOptional) {
    lt::GlbChunks out;  // points into the bytes read: they must outlive it
    const Bytes jsonOnly = glb({{lt::kGlbChunkJson, kJson}});
    ASSERT_TRUE(readChunks(jsonOnly, GlbLayout::Strict, out));
    EXPECT_EQ(out.json, kJson);
    EXPECT_EQ(out.bin, nullptr);
    EXPECT_EQ(out.binLength, 0u);
    const Bytes empty = glb({{lt::kGlbChunkJson, kJson}, {lt::kGlbChunkBin, ""}});  // present, empty
    ASSERT_TRUE(readChunks(empty, GlbLayout::Strict, out));
    EXPECT_EQ(out.bin, empty.data() + empty.size());
    EXPECT_EQ(out.binLength, 0u);
}

TEST(Glb, TruncatedHeader) {
    const Bytes b = plain();
    for (size_t n : {size_t(0), size_t(4), size_t(11)})
        expectFault(Bytes(b.begin(), b.begin() + long(n)),
                    "GLB header truncated: " + std::to_string(n) + " bytes, shorter than the 12-byte header");
    lt::GlbChunks out;
    EXPECT_FALSE(lt::readGlb(nullptr, 0, "t.glb", GlbLayout::Strict, out));
    EXPECT_FALSE(lt::isGlb(nullptr, 0));
    EXPECT_FALSE(lt::isGlb(b.data(), 3));
}

TEST(Glb, WrongMagicVersionOrLength) {
    Bytes b = plain();
    b[0] = 'X';
    expectFault(b, "not a GLB: magic is not 'glTF'");
    EXPECT_FALSE(lt::isGlb(b.data(), b.size()));
    b = plain();
    fmttest::putU32(b, 4, 1);
    expectFault(b, "GLB version 1, expected 2");
    b = plain();
    fmttest::putU32(b, 8, uint32_t(b.size() + 4));
    expectFault(b, "GLB header length 76 differs from the file size 72");
    b = plain();
    b.resize(b.size() - 4);  // cut short: the header still says 72
    expectFault(b, "GLB header length 72 differs from the file size 68");
}

TEST(Glb, ChunkPastTheEnd) {
    Bytes b = plain();
    fmttest::putU32(b, 12, uint32_t(kJson.size() + 400));
    expectFault(b, "GLB chunk 0: length 432 overruns the file (the chunk's data starts at byte 20 of 72)");
    b = plain();
    fmttest::putU32(b, 52, uint32_t(kBin.size() + 4));  // BIN claims 4 bytes more than there are
    expectFault(b, "GLB chunk 1: length 16 overruns the file");
    for (uint32_t huge : {0xFFFFFFFFu, 0xFFFFFFFCu}) {  // no wrap-around in the bounds arithmetic
        b = plain();
        fmttest::putU32(b, 52, huge);
        expectFault(b, "GLB chunk 1: length " + std::to_string(huge) + " ");
    }
    b = plain();
    b.insert(b.end(), {1, 2, 3, 4});  // 4 bytes: less than a chunk header
    fmttest::putU32(b, 8, uint32_t(b.size()));
    expectFault(b, "GLB chunk 2: header truncated at byte 72 (4 bytes left)");
}

TEST(Glb, UnalignedChunk) {
    // A 30-byte JSON chunk: Strict rejects it; Lenient reads it and finds the BIN
    // chunk at the unaligned offset that follows.
    const std::string json = kJson.substr(0, 30);
    const Bytes b = glb({{lt::kGlbChunkJson, json}, {lt::kGlbChunkBin, kBin}});
    const lt::GlbChunks out = expectLenientOnly(b, "t.glb: GLB chunk 0: length 30 is not a multiple of 4");
    EXPECT_EQ(out.json, json);
    EXPECT_EQ(text(out.bin, out.binLength), kBin);
    EXPECT_EQ(out.bin, b.data() + 20 + 30 + 8);
    expectLenientOnly(glb({{lt::kGlbChunkJson, kJson}, {lt::kGlbChunkBin, "abc"}}), "GLB chunk 1: length 3 is not");
}

TEST(Glb, JsonChunkFirstAndNotEmpty) {
    expectFault(glb({{lt::kGlbChunkBin, kBin}, {lt::kGlbChunkJson, kJson}}), "GLB chunk 0 is not JSON");
    expectFault(glb({{kOther, kBin}}), "GLB chunk 0 is not JSON");
    expectFault(glb({}), "GLB has no JSON chunk");
    const lt::GlbChunks out =
        expectLenientOnly(glb({{lt::kGlbChunkJson, ""}, {lt::kGlbChunkBin, kBin}}), "GLB JSON chunk is empty");
    EXPECT_TRUE(out.json.empty());
    EXPECT_EQ(out.binLength, kBin.size());
}

TEST(Glb, ExtraChunks) {
    // Unknown types are skipped by both, wherever they are.
    for (GlbLayout layout : {GlbLayout::Strict, GlbLayout::Lenient}) {
        lt::GlbChunks out;
        const Bytes last = glb({{lt::kGlbChunkJson, kJson}, {lt::kGlbChunkBin, kBin}, {kOther, "abcd"}});
        ASSERT_TRUE(readChunks(last, layout, out));
        EXPECT_EQ(text(out.bin, out.binLength), kBin);
        const Bytes noBin = glb({{lt::kGlbChunkJson, kJson}, {kOther, "abcd"}, {kOther, ""}});
        ASSERT_TRUE(readChunks(noBin, layout, out));
        EXPECT_EQ(out.json, kJson);
        EXPECT_EQ(out.bin, nullptr);
    }
    // JSON or BIN out of place: Strict rejects; Lenient skips them, keeping only
    // chunk 0 as the JSON and chunk 1 as the BIN.
    const Bytes binLate = glb({{lt::kGlbChunkJson, kJson}, {kOther, "abcd"}, {lt::kGlbChunkBin, kBin}});
    lt::GlbChunks out = expectLenientOnly(binLate, "t.glb: GLB chunk 2 is a BIN chunk, which only chunk 1 may be");
    EXPECT_EQ(out.bin, nullptr);
    const Bytes twoBins = glb({{lt::kGlbChunkJson, kJson}, {lt::kGlbChunkBin, kBin}, {lt::kGlbChunkBin, "abcd"}});
    out = expectLenientOnly(twoBins, "t.glb: GLB chunk 2 is a second BIN chunk");
    EXPECT_EQ(text(out.bin, out.binLength), kBin);
    const Bytes twoJsons = glb({{lt::kGlbChunkJson, kJson}, {lt::kGlbChunkBin, kBin}, {lt::kGlbChunkJson, "{}  "}});
    out = expectLenientOnly(twoJsons, "t.glb: GLB chunk 2 is a second JSON chunk");
    EXPECT_EQ(out.json, kJson);
}

// The format's reader cites spec rules 1 and 2 for what readGlb rejects, with its words.
TEST(Glb, AssetReaderCitesTheRule) {
    Bytes b = fmttest::write(fmttest::makeAsset(false));
    fmttest::putU32(b, 4, 3);
    lt::Asset a;
    lt::Status st = lt::readAssetGlb(b.data(), b.size(), "t.glb", a);
    EXPECT_EQ(st.message, "t.glb: rule 1: GLB version 3, expected 2");
    b = glb({{lt::kGlbChunkJson, kJson.substr(0, 30)}});
    st = lt::readAssetGlb(b.data(), b.size(), "t.glb", a);
    EXPECT_EQ(st.message, "t.glb: rule 2: GLB chunk 0: length 30 is not a multiple of 4");
}

// Contract: any bytes are safe, and what is read lies inside them. Every prefix and
// every single byte changed (to 0xFF and to 0x00) of a file with an unknown chunk.
TEST(Glb, AnyBytesAreSafe) {
    const Bytes good = glb({{lt::kGlbChunkJson, kJson}, {lt::kGlbChunkBin, kBin}, {kOther, "abcd"}});
    auto check = [](const Bytes& b) {
        for (GlbLayout layout : {GlbLayout::Strict, GlbLayout::Lenient}) {
            lt::GlbChunks out;
            if (!readChunks(b, layout, out)) continue;
            const char* begin = reinterpret_cast<const char*>(b.data());
            EXPECT_TRUE(out.json.data() >= begin && out.json.data() + out.json.size() <= begin + b.size());
            EXPECT_TRUE(!out.bin || (out.bin >= b.data() && out.bin + out.binLength <= b.data() + b.size()));
        }
    };
    for (size_t n = 0; n <= good.size(); ++n) check(Bytes(good.begin(), good.begin() + long(n)));
    for (size_t i = 0; i < good.size(); ++i)
        for (uint8_t v : {uint8_t(0xFF), uint8_t(0)}) {
            Bytes b = good;
            b[i] = v;
            check(b);
        }
}

}  // namespace
