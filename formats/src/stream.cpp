// formats/src/stream.cpp -- the byte-plane + Zstandard table stream (stream.h).
#include "stream.h"

#include <zstd.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// The planes of one part (values x size little-endian bytes) appended to `out`,
// then its padding.
void appendPlanes(const StreamPart& p, std::vector<uint8_t>& out) {
    const size_t at = out.size(), n = p.values;
    out.resize(at + size_t(segmentBytes(n, uint64_t(p.size))), 0);
    uint8_t* dst = out.data() + at;
    for (int b = 0; b < p.size; ++b)
        for (size_t i = 0; i < n; ++i) dst[size_t(b) * n + i] = p.data[i * size_t(p.size) + size_t(b)];
}

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
        const __m128i lo01 = _mm_unpacklo_epi8(b0, b1), hi01 = _mm_unpackhi_epi8(b0, b1);   // bytes 0,1 of values
        const __m128i lo23 = _mm_unpacklo_epi8(b2, b3), hi23 = _mm_unpackhi_epi8(b2, b3);   // bytes 2,3
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

} // namespace

bool encodeStream(const std::vector<StreamPart>& parts, int level, std::vector<uint8_t>& out,
                  std::vector<size_t>& groupBytes) {
    std::unique_ptr<ZSTD_CCtx, CCtxFree> cctx(ZSTD_createCCtx());
    if (!cctx) return false;
    uint64_t total = 0;
    for (const StreamPart& p : parts) total += segmentBytes(p.values, uint64_t(p.size));
    if (ZSTD_isError(ZSTD_CCtx_setParameter(cctx.get(), ZSTD_c_compressionLevel, level)) ||
        ZSTD_isError(ZSTD_CCtx_setParameter(cctx.get(), ZSTD_c_checksumFlag, 0)) ||
        ZSTD_isError(ZSTD_CCtx_setPledgedSrcSize(cctx.get(), total)))
        return false;
    out.assign(ZSTD_compressBound(size_t(total)), 0);
    ZSTD_outBuffer dst{out.data(), out.size(), 0};
    std::vector<uint8_t> planes;
    size_t groupStart = 0;
    for (size_t k = 0; k < parts.size(); ++k) {
        planes.clear();
        appendPlanes(parts[k], planes);
        const bool last = k + 1 == parts.size();
        const bool groupEnds = last || parts[k + 1].group != parts[k].group;
        const ZSTD_EndDirective mode = last ? ZSTD_e_end : groupEnds ? ZSTD_e_flush : ZSTD_e_continue;
        ZSTD_inBuffer src{planes.data(), planes.size(), 0};
        size_t remaining;
        do {
            remaining = ZSTD_compressStream2(cctx.get(), &dst, &src, mode);
            if (ZSTD_isError(remaining)) return false;
        } while (src.pos < src.size || (mode != ZSTD_e_continue && remaining != 0));
        if (!groupEnds) continue;
        const size_t g = size_t(parts[k].group);
        if (groupBytes.size() <= g) groupBytes.resize(g + 1, 0);
        groupBytes[g] += dst.pos - groupStart;
        groupStart = dst.pos;
    }
    out.resize(dst.pos);
    return true;
}

bool decodeStream(const uint8_t* data, size_t length, uint64_t decodedBytes, const std::vector<Segment>& segments,
                  std::unique_ptr<uint8_t[]>& out, std::string& error) {
    const unsigned long long declared = ZSTD_getFrameContentSize(data, length);
    if (declared == ZSTD_CONTENTSIZE_ERROR) {
        error = "is not a Zstandard frame";
        return false;
    }
    if (declared == ZSTD_CONTENTSIZE_UNKNOWN) {
        error = "its Zstandard frame does not declare its content size";
        return false;
    }
    if (ZSTD_findFrameCompressedSize(data, length) != length) {
        error = "holds bytes after its Zstandard frame, or a truncated frame";
        return false;
    }
    if (declared != decodedBytes) {
        error = "its Zstandard frame declares " + std::to_string(declared) + " bytes, its accessors need " +
                std::to_string(decodedBytes);
        return false;
    }
    // Decoded in place: Zstandard writes the planes into `out`, then each segment
    // of wider values goes through `scratch` back into `out` as values. (Bytes of
    // single-byte segments are their values already; padding is never read.)
    out.reset(new uint8_t[size_t(decodedBytes)]);
    std::unique_ptr<ZSTD_DCtx, DCtxFree> dctx(ZSTD_createDCtx());
    if (!dctx) throw std::bad_alloc();
    const size_t got = ZSTD_decompressDCtx(dctx.get(), out.get(), size_t(decodedBytes), data, length);
    if (ZSTD_isError(got) || got != decodedBytes) {
        error = std::string("its Zstandard frame is corrupt or truncated (") +
                (ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short") + ")";
        return false;
    }
    std::vector<uint8_t> scratch;
    for (const Segment& s : segments) {
        if (s.size == 1) continue;
        const size_t bytes = size_t(s.values) * size_t(s.size);
        scratch.assign(out.get() + s.offset, out.get() + s.offset + bytes);
        interleave(scratch.data(), size_t(s.values), s.size, out.get() + s.offset);
    }
    return true;
}

} // namespace lt::fmt
