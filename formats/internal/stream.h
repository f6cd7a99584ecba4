// formats/internal/stream.h -- private to looptess_formats: the compressed table stream of
// a surface (spec "Compression", rule 46), encoded by the writer and decoded by the
// reader. No JSON here: the callers map accessors to segments.
//
// A stream holds the values of a list of accessors, one segment each, in list
// order. A segment stores an accessor's n values (count x components) of s bytes
// (its componentType's size) as s byte planes, least significant first, then zero
// bytes up to a multiple of 4:
//
//   values      v0 = 0x0201   v1 = 0x0403   v2 = 0x0605          (n = 3, s = 2)
//   little end  01 02 | 03 04 | 05 06
//   segment     01 03 05 | 02 04 06 | 00 00                       (plane 0 | plane 1 | pad)
//
// Neighbouring values of a table differ mostly in their low bytes, so the planes
// of the high bytes are long runs that the general-purpose stage (one Zstandard
// frame over all segments) removes. The decoded stream is the segments back in
// little-endian order: each accessor's tightly packed glTF bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace lt::fmt {

inline constexpr const char* kStreamMethod = "BYTE_PLANES_ZSTD";
// Rule 46: a stream decodes to at most this many times its encoded bytes. The
// writer stores tables uncompressed where they would exceed it.
inline constexpr uint64_t kMaxStreamRatio = 256;

// The reference writer's frame size at --compress fast (decoded bytes; the last
// frame holds the rest), so that readers can decode the frames of a large stream
// on several threads. Readers accept frames of any size; a reader starts threads
// for streams of at least twice this.
inline constexpr uint64_t kFrameBytes = uint64_t(8) << 20;
// Most threads a reader decodes one stream on (the calling thread included).
inline constexpr size_t kMaxThreads = 8;

// Bytes of one segment: n values of s bytes, padded to a multiple of 4.
inline uint64_t segmentBytes(uint64_t values, uint64_t size) { return (values * size + 3) / 4 * 4; }

// One accessor's values for the writer: little-endian, tightly packed.
struct StreamPart {
    const uint8_t* data = nullptr;
    size_t values = 0;
    int size = 0;   // bytes per value: 1, 2 or 4
    int group = 0;  // what groupBytes attributes the part's bytes to; see encodeStream
};

// Zstandard's settings for a stream: a compression level and, where not 0, the
// match finder's table sizes (log2 of entries) and shortest match in place of the
// level's own.
struct ZstdSettings {
    int level = 3;
    int hashLog = 0, chainLog = 0, minMatch = 0;
};

// Encodes `parts` (in order) with `zstd` into `out` (replaced): one Zstandard frame
// per `frameBytes` of decoded stream, back to back, the frames on up to `threads`
// threads (parallel.h's count: 0, one per core). `groupBytes[g]` receives the
// encoded bytes that group g's parts take: each frame's output apportioned to its
// parts by their decoded bytes, exactly at the frame's block boundaries (every 128
// KiB of planes) and linearly between them; the groups add up to out.size().
// Deterministic for a given zstd version, the same bytes for every thread count.
// False only when out of memory or zstd fails.
bool encodeStream(const std::vector<StreamPart>& parts, const ZstdSettings& zstd, uint64_t frameBytes, size_t threads,
                  std::vector<uint8_t>& out, std::vector<size_t>& groupBytes);

struct FreeBytes {
    void operator()(uint8_t* p) const { std::free(p); }
};
using StreamBytes = std::unique_ptr<uint8_t[], FreeBytes>;

// At least `bytes` of uninitialized memory for a decoded stream (on Linux, huge
// pages where the kernel has them). Throws std::bad_alloc.
StreamBytes allocateStream(size_t bytes);

// One segment of a stream being decoded: where it starts in the decoded stream
// and its layout.
struct Segment {
    uint64_t offset = 0, values = 0;
    int size = 0;
};

// Decodes `length` bytes at `data` into `out`: checks that they are Zstandard
// frames back to back, each declaring its content size, whose sizes add up to
// `decodedBytes` (the sum of the segments' bytes, which the caller has bounded),
// decodes them (large streams on several threads) and turns each segment's planes
// back into little-endian values (the bytes of `out` past a segment's values, its
// padding, are unspecified). On failure returns false with `error` saying what is
// wrong (no allocation happens before the sizes agree). Throws std::bad_alloc.
bool decodeStream(const uint8_t* data, size_t length, uint64_t decodedBytes, const std::vector<Segment>& segments,
                  StreamBytes& out, std::string& error);

}  // namespace lt::fmt
