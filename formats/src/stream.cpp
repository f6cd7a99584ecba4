// formats/src/stream.cpp -- the byte-plane + Zstandard table stream (stream.h).
#include "stream.h"

#include "huge_pages.h"
#include "parallel.h"

// ZSTD_getFrameProgression (groupBytes) is declared among the advanced API; libzstd
// has exported it since 1.3.x.
#define ZSTD_STATIC_LINKING_ONLY
#include <zstd.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>

namespace lt::fmt {
namespace {

#if defined(__SSE2__)
__m128i load(const uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); }
void store(uint8_t* p, __m128i v) { _mm_storeu_si128(reinterpret_cast<__m128i*>(p), v); }
#endif

struct CCtxFree {
    void operator()(ZSTD_CCtx* c) const { ZSTD_freeCCtx(c); }
};
struct DCtxFree {
    void operator()(ZSTD_DCtx* c) const { ZSTD_freeDCtx(c); }
};

// Planes of one segment at `src` back to little-endian values at `dst` (size 2 or
// 4). SSE2 (every x86-64) interleaves 16 values per step; the scalar loop does
// the rest and other targets.
void interleave(const uint8_t* src, size_t n, int size, uint8_t* dst) {
    const uint8_t *p0 = src, *p1 = src + n, *p2 = src + 2 * n, *p3 = src + 3 * n;
    size_t i = 0;
    if (size == 2) {
#if defined(__SSE2__)
        for (; i + 16 <= n; i += 16) {
            const __m128i b0 = load(p0 + i), b1 = load(p1 + i);
            store(dst + 2 * i, _mm_unpacklo_epi8(b0, b1));
            store(dst + 2 * i + 16, _mm_unpackhi_epi8(b0, b1));
        }
#endif
        for (; i < n; ++i) {
            dst[2 * i] = p0[i];
            dst[2 * i + 1] = p1[i];
        }
        return;
    }
#if defined(__SSE2__)
    for (; i + 16 <= n; i += 16) {
        const __m128i b0 = load(p0 + i), b1 = load(p1 + i), b2 = load(p2 + i), b3 = load(p3 + i);
        const __m128i lo01 = _mm_unpacklo_epi8(b0, b1), hi01 = _mm_unpackhi_epi8(b0, b1);  // bytes 0,1 of values
        const __m128i lo23 = _mm_unpacklo_epi8(b2, b3), hi23 = _mm_unpackhi_epi8(b2, b3);  // bytes 2,3
        store(dst + 4 * i, _mm_unpacklo_epi16(lo01, lo23));
        store(dst + 4 * i + 16, _mm_unpackhi_epi16(lo01, lo23));
        store(dst + 4 * i + 32, _mm_unpacklo_epi16(hi01, hi23));
        store(dst + 4 * i + 48, _mm_unpackhi_epi16(hi01, hi23));
    }
#endif
    for (; i < n; ++i) {
        dst[4 * i] = p0[i];
        dst[4 * i + 1] = p1[i];
        dst[4 * i + 2] = p2[i];
        dst[4 * i + 3] = p3[i];
    }
}

// `n` little-endian values of N bytes at `src` as N planes at `dst` (interleave's
// inverse), in one pass over the values. SSE2 splits 16 values per step: three
// rounds of byte unpacking gather bytes 0 and 1 of values 0-7 in one register's
// halves (and bytes 2 and 3 in the next), the 64-bit halves then pair them with
// values 8-15's; 2-byte values are split by masking and packing. The scalar loop
// does the rest and other targets.
template <int N>
void toPlanes(const uint8_t* src, size_t n, uint8_t* dst) {
    size_t i = 0;
#if defined(__SSE2__)
    if constexpr (N == 4) {
        uint8_t *p0 = dst, *p1 = dst + n, *p2 = dst + 2 * n, *p3 = dst + 3 * n;
        for (; i + 16 <= n; i += 16) {
            const uint8_t* s = src + 4 * i;
            __m128i a0 = _mm_unpacklo_epi8(load(s), load(s + 16)), a1 = _mm_unpackhi_epi8(load(s), load(s + 16));
            __m128i a2 = _mm_unpacklo_epi8(load(s + 32), load(s + 48));
            __m128i a3 = _mm_unpackhi_epi8(load(s + 32), load(s + 48));
            const __m128i b0 = _mm_unpacklo_epi8(a0, a1), b1 = _mm_unpackhi_epi8(a0, a1);
            const __m128i b2 = _mm_unpacklo_epi8(a2, a3), b3 = _mm_unpackhi_epi8(a2, a3);
            a0 = _mm_unpacklo_epi8(b0, b1), a1 = _mm_unpackhi_epi8(b0, b1);  // values 0-7: bytes 0|1, 2|3
            a2 = _mm_unpacklo_epi8(b2, b3), a3 = _mm_unpackhi_epi8(b2, b3);  // values 8-15
            store(p0 + i, _mm_unpacklo_epi64(a0, a2));
            store(p1 + i, _mm_unpackhi_epi64(a0, a2));
            store(p2 + i, _mm_unpacklo_epi64(a1, a3));
            store(p3 + i, _mm_unpackhi_epi64(a1, a3));
        }
    } else if constexpr (N == 2) {
        const __m128i low = _mm_set1_epi16(0xFF);
        uint8_t *p0 = dst, *p1 = dst + n;
        for (; i + 16 <= n; i += 16) {
            const __m128i v0 = load(src + 2 * i), v1 = load(src + 2 * i + 16);
            store(p0 + i, _mm_packus_epi16(_mm_and_si128(v0, low), _mm_and_si128(v1, low)));
            store(p1 + i, _mm_packus_epi16(_mm_srli_epi16(v0, 8), _mm_srli_epi16(v1, 8)));
        }
    }
#endif
    for (; i < n; ++i)
        for (int b = 0; b < N; ++b) dst[size_t(b) * n + i] = src[N * i + size_t(b)];
}

// Runs body(task, worker) for task 0 .. tasks - 1 (parallel.h), on up to kMaxThreads
// threads when `bytes` of work make threads worth starting, else in order on the
// calling thread.
template <class F>
void decodeTasks(size_t tasks, uint64_t bytes, F body) {
    parallelTasks(tasks, bytes < 2 * kFrameBytes ? 1 : std::min(kMaxThreads, threadCount(0)), body);
}

// `cctx` set up for a frame of `bytes` with `zstd`: its content size declared (the
// reader requires it), no checksum.
bool configure(ZSTD_CCtx* cctx, const ZstdSettings& zstd, uint64_t bytes) {
    const std::pair<ZSTD_cParameter, int> settings[] = {{ZSTD_c_compressionLevel, zstd.level},
                                                        {ZSTD_c_checksumFlag, 0},
                                                        {ZSTD_c_hashLog, zstd.hashLog},
                                                        {ZSTD_c_chainLog, zstd.chainLog},
                                                        {ZSTD_c_minMatch, zstd.minMatch}};
    for (const auto& [param, value] : settings)
        if (ZSTD_isError(ZSTD_CCtx_setParameter(cctx, param, value))) return false;
    return !ZSTD_isError(ZSTD_CCtx_setPledgedSrcSize(cctx, bytes));
}

// Where plane byte `at` of a frame ends up in its output: `progress` holds (planes
// compressed, bytes produced) pairs, ascending, from (0, 0) to the whole frame;
// between two of them the output is taken as proportional to the planes.
uint64_t apportioned(const std::vector<std::pair<uint64_t, uint64_t>>& progress, uint64_t at) {
    const auto hi = std::lower_bound(progress.begin(), progress.end(), std::make_pair(at, uint64_t(0)));
    if (hi == progress.end()) return progress.back().second;
    if (hi->first == at || hi == progress.begin()) return hi->second;
    const auto lo = hi - 1;
    return lo->second + (hi->second - lo->second) * (at - lo->first) / (hi->first - lo->first);
}

}  // namespace

bool encodeStream(const std::vector<StreamPart>& parts, const ZstdSettings& zstd, uint64_t frameBytes, size_t threads,
                  std::vector<uint8_t>& out, std::vector<size_t>& groupBytes) {
    // Every part's planes, back to back (each part on one thread).
    std::vector<uint64_t> partAt(parts.size() + 1, 0);
    for (size_t k = 0; k < parts.size(); ++k)
        partAt[k + 1] = partAt[k] + segmentBytes(parts[k].values, uint64_t(parts[k].size));
    const uint64_t total = partAt.back();
    // Every byte is written below, the padding to 4 bytes zeroed: no zeroing pass
    // over the whole buffer first (as for the frames' buffers).
    const std::unique_ptr<uint8_t[]> planes(new uint8_t[size_t(total)]);
    parallelTasks(parts.size(), threads, [&](size_t k, size_t) {
        const StreamPart& p = parts[k];
        uint8_t* dst = planes.get() + partAt[k];
        switch (p.size) {
        case 4: toPlanes<4>(p.data, p.values, dst); break;
        case 2: toPlanes<2>(p.data, p.values, dst); break;
        default:
            for (int b = 0; b < p.size; ++b)
                for (size_t i = 0; i < p.values; ++i)
                    dst[size_t(b) * p.values + i] = p.data[i * size_t(p.size) + size_t(b)];
        }
        const size_t written = p.values * size_t(p.size);
        std::fill(dst + written, planes.get() + partAt[k + 1], uint8_t(0));
    });
    // The frames are independent: each is compressed on its own (one a thread),
    // fed in the same pieces -- cut where a part or a frame ends -- as one context
    // writing them in turn would be, then concatenated in order. No piece is
    // flushed early: a flush where each group ends (for exact groupBytes) made
    // fandisk's stream 2.4% larger at level 4, and 26% with a smaller match finder
    // (bench/README.md). Instead the context's progress after each piece
    // -- planes compressed, bytes produced, which move a block at a time -- places
    // the ends of the groups in the output, interpolated within a block.
    const size_t frames = size_t(total == 0 ? 0 : (total + frameBytes - 1) / frameBytes);
    struct Frame {
        std::unique_ptr<uint8_t[]> bytes;  // Zstandard's bound, of which `size` are written
        size_t size = 0;
        std::vector<std::pair<size_t, size_t>> groupEnds;  // (group, end in the output)
        bool ok = false;
    };
    std::vector<Frame> encoded(frames);
    parallelTasks(frames, threads, [&](size_t f, size_t) {
        Frame& frame = encoded[f];
        const uint64_t from = uint64_t(f) * frameBytes, to = std::min(total, from + frameBytes);
        std::unique_ptr<ZSTD_CCtx, CCtxFree> cctx(ZSTD_createCCtx());
        if (!cctx || !configure(cctx.get(), zstd, to - from)) return;
        const size_t bound = ZSTD_compressBound(size_t(to - from)) + 64;
        frame.bytes.reset(new uint8_t[bound]);
        ZSTD_outBuffer dst{frame.bytes.get(), bound, 0};
        std::vector<std::pair<uint64_t, uint64_t>> progress{{0, 0}};  // (planes compressed, bytes produced)
        size_t k = f == 0 ? 0 : size_t(std::upper_bound(partAt.begin() + 1, partAt.end(), from) - partAt.begin()) - 1;
        for (; k < parts.size() && partAt[k] < to; ++k) {
            const uint64_t at = std::max(from, partAt[k]), end = std::min(to, partAt[k + 1]);
            if (end > at) {  // (an empty part has nothing to feed: a single context skips it too)
                const ZSTD_EndDirective mode = end == to ? ZSTD_e_end : ZSTD_e_continue;
                ZSTD_inBuffer src{planes.get() + at, size_t(end - at), 0};
                size_t remaining;
                do {
                    remaining = ZSTD_compressStream2(cctx.get(), &dst, &src, mode);
                    if (ZSTD_isError(remaining)) return;
                } while (src.pos < src.size || (mode == ZSTD_e_end && remaining != 0));
                const ZSTD_frameProgression p = ZSTD_getFrameProgression(cctx.get());
                progress.push_back(
                    {mode == ZSTD_e_end ? to - from : p.consumed, mode == ZSTD_e_end ? dst.pos : p.produced});
            }
            if (end == partAt[k + 1] && (k + 1 == parts.size() || parts[k + 1].group != parts[k].group))
                frame.groupEnds.push_back({size_t(parts[k].group), size_t(end - from)});  // in planes, for now
        }
        for (auto& [g, end] : frame.groupEnds) end = size_t(apportioned(progress, end));
        frame.size = dst.pos;
        frame.ok = true;
    });
    out.clear();
    size_t groupStart = 0;
    for (const Frame& frame : encoded) {
        if (!frame.ok) return false;
        const size_t base = out.size();
        out.insert(out.end(), frame.bytes.get(), frame.bytes.get() + frame.size);
        for (const auto& [g, end] : frame.groupEnds) {
            if (groupBytes.size() <= g) groupBytes.resize(g + 1, 0);
            groupBytes[g] += base + end - groupStart;
            groupStart = base + end;
        }
    }
    return true;
}

StreamBytes allocateStream(size_t bytes) {
    // Huge pages: decoding touches every page once, and on a virtual machine a 31 MB
    // stream's 7,600 faults of 4 KiB pages took as long as Zstandard itself
    // (bench/README.md "Why the tables are encoded as they are").
    void* p = allocateHugePages(bytes);
    if (!p) throw std::bad_alloc();
    return StreamBytes(static_cast<uint8_t*>(p));
}

bool decodeStream(const uint8_t* data, size_t length, uint64_t decodedBytes, const std::vector<Segment>& segments,
                  StreamBytes& out, std::string& error) {
    // The frames, back to back: each declares its content size, and they add up
    // to the segments' bytes, all before anything is allocated.
    struct Frame {
        size_t from = 0, length = 0;
        uint64_t to = 0, bytes = 0;
    };
    std::vector<Frame> frames;
    uint64_t declared = 0;
    for (size_t at = 0; at < length;) {
        auto which = [&] { return "its Zstandard frame " + std::to_string(frames.size()); };
        const unsigned long long content = ZSTD_getFrameContentSize(data + at, length - at);
        if (content == ZSTD_CONTENTSIZE_ERROR) {
            error = frames.empty() ? "is not a Zstandard frame"
                                   : which() + " (at byte " + std::to_string(at) + ") is not a Zstandard frame";
            return false;
        }
        if (content == ZSTD_CONTENTSIZE_UNKNOWN) {
            error = which() + " does not declare its content size";
            return false;
        }
        const size_t size = ZSTD_findFrameCompressedSize(data + at, length - at);
        if (ZSTD_isError(size)) {
            error = which() + " is truncated";
            return false;
        }
        if (content > decodedBytes - declared) {
            error = "its Zstandard frames declare more than the " + std::to_string(decodedBytes) +
                    " bytes its accessors need";
            return false;
        }
        frames.push_back(Frame{at, size, declared, content});
        declared += content;
        at += size;
    }
    if (declared != decodedBytes) {
        error = "its Zstandard frames declare " + std::to_string(declared) + " bytes, its accessors need " +
                std::to_string(decodedBytes);
        return false;
    }
    // Decoded in place: Zstandard writes the planes into `out`, then each segment
    // of wider values goes through a scratch copy back into `out` as values. (Bytes
    // of single-byte segments are their values already; padding is never read.)
    out = allocateStream(size_t(decodedBytes));
    std::vector<std::string> errors(frames.size());
    std::unique_ptr<ZSTD_DCtx, DCtxFree> dctx[kMaxThreads];  // one per worker
    decodeTasks(frames.size(), decodedBytes, [&](size_t f, size_t worker) {
        if (!dctx[worker]) dctx[worker].reset(ZSTD_createDCtx());
        if (!dctx[worker]) throw std::bad_alloc();
        const Frame& fr = frames[f];
        const size_t got =
            ZSTD_decompressDCtx(dctx[worker].get(), out.get() + fr.to, size_t(fr.bytes), data + fr.from, fr.length);
        if (ZSTD_isError(got) || got != fr.bytes)
            errors[f] = "its Zstandard frame " + std::to_string(f) + " is corrupt or truncated (" +
                        (ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short") + ")";
    });
    for (const std::string& e : errors)
        if (!e.empty()) {
            error = e;
            return false;
        }
    // Largest segments first, so that the threads finish together.
    std::vector<const Segment*> wide;
    for (const Segment& s : segments)
        if (s.size > 1) wide.push_back(&s);
    std::stable_sort(wide.begin(), wide.end(),
                     [](const Segment* a, const Segment* b) { return a->values > b->values; });
    std::vector<uint8_t> scratch[kMaxThreads];  // one per worker
    decodeTasks(wide.size(), decodedBytes, [&](size_t k, size_t worker) {
        const Segment& s = *wide[k];
        const size_t bytes = size_t(s.values) * size_t(s.size);
        scratch[worker].assign(out.get() + s.offset, out.get() + s.offset + bytes);
        interleave(scratch[worker].data(), size_t(s.values), s.size, out.get() + s.offset);
    });
    return true;
}

}  // namespace lt::fmt
