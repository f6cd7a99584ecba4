// tests/formats/test_format_stream.cpp -- the table stream codec itself (formats/internal/stream.h):
// a stream of many frames, larger than the size from which the reader decodes on
// several threads, round-trips bit for bit, encodes to the same bytes on any number of
// threads, gives each group of parts its share of the bytes, and a damaged frame in its middle is
// an error naming that frame, whichever thread meets it.
#include "stream.h"

#include <gtest/gtest.h>
#include <zstd.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

using lt::fmt::Segment;
using lt::fmt::StreamPart;

// Segments of 4-, 2- and 1-byte values (counts not multiples of 4: padding), over
// twice kFrameBytes in all, each a slowly varying pattern that planes compress.
struct Parts {
    std::vector<uint32_t> wide;
    std::vector<uint16_t> narrow;
    std::vector<uint8_t> bytes;
    std::vector<StreamPart> parts;
    std::vector<Segment> segments;
    uint64_t total = 0;

    Parts() {
        const size_t n = size_t(lt::fmt::kFrameBytes) / 2 + 3;
        for (size_t i = 0; i < n; ++i) wide.push_back(uint32_t(i * 7 + (i % 13) * 65536));
        for (size_t i = 0; i < n + 1; ++i) narrow.push_back(uint16_t(i * 3 ^ (i >> 9)));
        for (size_t i = 0; i < n + 2; ++i) bytes.push_back(uint8_t(i % 251));
        add(wide.data(), wide.size(), 4);
        add(narrow.data(), narrow.size(), 2);
        add(bytes.data(), bytes.size(), 1);
        add(wide.data(), wide.size(), 4);  // the same again: a second wide segment
    }
    void add(const void* data, size_t values, int size) {
        parts.push_back(StreamPart{static_cast<const uint8_t*>(data), values, size, int(parts.size())});
        segments.push_back(Segment{total, values, size});
        total += lt::fmt::segmentBytes(values, uint64_t(size));
    }
};

TEST(StreamCodec, ManyFramesOnSeveralThreadsRoundTrip) {
    const Parts p;
    ASSERT_GE(p.total, 2 * lt::fmt::kFrameBytes);  // the reader's threshold for threads
    std::vector<uint8_t> encoded;
    std::vector<size_t> groups;
    ASSERT_TRUE(lt::fmt::encodeStream(p.parts, {1}, (1 << 20) + 3, 0, encoded, groups));  // ~21 frames
    size_t groupTotal = 0;
    for (size_t g : groups) groupTotal += g;
    EXPECT_EQ(groupTotal, encoded.size());
    lt::fmt::StreamBytes out;
    std::string error;
    ASSERT_TRUE(lt::fmt::decodeStream(encoded.data(), encoded.size(), p.total, p.segments, out, error)) << error;
    for (size_t k = 0; k < p.parts.size(); ++k) {
        SCOPED_TRACE("segment " + std::to_string(k));
        const StreamPart& part = p.parts[k];
        EXPECT_EQ(std::memcmp(out.get() + p.segments[k].offset, part.data, part.values * size_t(part.size)), 0);
    }
}

// The frames are encoded on several threads: the same bytes and group sizes for
// every count, whether a part spans frames (the wide ones) or a frame holds several.
TEST(StreamCodec, SameBytesOnEveryThreadCount) {
    const Parts p;
    std::vector<uint8_t> serial;
    std::vector<size_t> serialGroups;
    ASSERT_TRUE(lt::fmt::encodeStream(p.parts, {1}, (1 << 20) + 3, 1, serial, serialGroups));
    for (size_t threads : {2, 3, 8}) {
        SCOPED_TRACE(std::to_string(threads) + " threads");
        std::vector<uint8_t> encoded;
        std::vector<size_t> groups;
        ASSERT_TRUE(lt::fmt::encodeStream(p.parts, {1}, (1 << 20) + 3, threads, encoded, groups));
        EXPECT_TRUE(encoded == serial);
        EXPECT_EQ(groups, serialGroups);
    }
}

// Each group's share of the stream follows what its planes compress to: 1 MiB of
// noise, then 1 MiB of zeros, then noise again, in one frame, take about 1 MiB,
// almost nothing and 1 MiB (the groups end on Zstandard's 128 KiB blocks).
TEST(StreamCodec, GroupBytesAreWhatEachGroupCompressesTo) {
    constexpr size_t kMiB = size_t(1) << 20;
    std::vector<uint8_t> noise(2 * kMiB), zeros(kMiB, 0);
    std::mt19937 random(7);
    for (uint8_t& b : noise) b = uint8_t(random() >> 24);
    const std::vector<StreamPart> parts = {
        {noise.data(), kMiB, 1, 0}, {zeros.data(), kMiB, 1, 1}, {noise.data() + kMiB, kMiB, 1, 2}};
    std::vector<uint8_t> encoded;
    std::vector<size_t> groups;
    ASSERT_TRUE(lt::fmt::encodeStream(parts, {4}, 8 * kMiB, 1, encoded, groups));
    ASSERT_EQ(groups.size(), 3u);
    EXPECT_EQ(groups[0] + groups[1] + groups[2], encoded.size());
    for (size_t g : {0, 2}) {
        EXPECT_GT(groups[g], kMiB);  // noise does not compress: a little over its bytes
        EXPECT_LT(groups[g], kMiB + kMiB / 64);
    }
    EXPECT_LT(groups[1], kMiB / 256);
}

TEST(StreamCodec, ADamagedFrameInTheMiddleIsNamed) {
    const Parts p;
    std::vector<uint8_t> encoded;
    std::vector<size_t> groups;
    ASSERT_TRUE(lt::fmt::encodeStream(p.parts, {1}, 1 << 20, 0, encoded, groups));
    // Frame 5's magic number, found by walking the frames.
    size_t at = 0;
    for (int f = 0; f < 5; ++f) at += ZSTD_findFrameCompressedSize(encoded.data() + at, encoded.size() - at);
    encoded[at] ^= 0xFF;
    lt::fmt::StreamBytes out;
    std::string error;
    EXPECT_FALSE(lt::fmt::decodeStream(encoded.data(), encoded.size(), p.total, p.segments, out, error));
    EXPECT_NE(error.find("frame 5"), std::string::npos) << error;
}

}  // namespace
