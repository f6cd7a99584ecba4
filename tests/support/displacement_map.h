// tests/support/displacement_map.h -- procedural displacement maps for the tests: a smooth,
// periodic, asymmetric pattern, written as a deterministic grayscale PNG.
//
// stb_image_write only writes 8-bit PNGs, so 16-bit (and 8-bit) gray PNGs come from
// the small encoder below: stored (uncompressed) deflate blocks, filter 0, CRC-32
// and Adler-32 as the PNG and zlib specs define them. Bytes depend on nothing but
// the arguments (the pattern is a polynomial: no libm approximations).
//
//   std::vector<uint8_t> png = lt::test::patternPng(256, 256, 16);
//   double expected = lt::test::displacementPattern(u, v);   // at a glTF UV
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace lt::test {

// The pattern at texture coordinate (s, t) (glTF: t down from the image's top),
// in [0.15, 0.85]. Period 1 in s and t and C1 across the period, so a repeat-wrapped
// bilinear read has no seam; its peak at (1/2, 1/4) tells a flipped or transposed
// read from a right one.
inline double displacementPattern(double s, double t) {
    auto bump = [](double x) {  // 16 x^2 (1 - x)^2 on the fractional part: 0 at 0 and 1, 1 at 1/2
        x -= std::floor(x);
        return 16.0 * x * x * (1.0 - x) * (1.0 - x);
    };
    return 0.15 + 0.7 * bump(s) * bump(t + 0.25);
}

// Texel (x, y) of a width x height map of the pattern, in 16-bit units: the pattern
// at the texel's centre ((x + 0.5) / width, (y + 0.5) / height).
inline uint16_t patternTexel(uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
    const double v = displacementPattern((x + 0.5) / width, (y + 0.5) / height);
    return uint16_t(std::floor(v * 65535.0 + 0.5));
}

namespace detail {

inline void putBE32(std::vector<uint8_t>& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(uint8_t(v >> s));
}

inline uint32_t crc32(const uint8_t* data, size_t n) {
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; ++i) {
        c ^= data[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c ^ 0xffffffffu;
}

inline void chunk(std::vector<uint8_t>& out, const char type[4], const std::vector<uint8_t>& payload) {
    putBE32(out, uint32_t(payload.size()));
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), payload.begin(), payload.end());
    putBE32(out, crc32(out.data() + start, out.size() - start));
}

}  // namespace detail

// A grayscale PNG (colour type 0) of `texels` (width * height, row 0 at the top),
// bit depth 8 (texels must be < 256) or 16.
inline std::vector<uint8_t> grayPng(uint32_t width, uint32_t height, int depth, const std::vector<uint16_t>& texels) {
    std::vector<uint8_t> raw;  // scanlines: filter byte 0, then big-endian samples
    for (uint32_t y = 0; y < height; ++y) {
        raw.push_back(0);
        for (uint32_t x = 0; x < width; ++x) {
            const uint16_t t = texels[size_t(y) * width + x];
            if (depth == 16) raw.push_back(uint8_t(t >> 8));
            raw.push_back(uint8_t(t));
        }
    }
    std::vector<uint8_t> z = {0x78, 0x01};  // zlib header: deflate, 32K window, no dictionary
    size_t at = 0;
    do {  // stored blocks of at most 65535 bytes
        const size_t n = raw.size() - at < 65535 ? raw.size() - at : 65535;
        z.push_back(at + n == raw.size() ? 1 : 0);  // BFINAL, BTYPE 00
        z.push_back(uint8_t(n));
        z.push_back(uint8_t(n >> 8));
        z.push_back(uint8_t(~n));
        z.push_back(uint8_t(~n >> 8));
        z.insert(z.end(), raw.begin() + std::ptrdiff_t(at), raw.begin() + std::ptrdiff_t(at + n));
        at += n;
    } while (at < raw.size());
    uint32_t a = 1, b = 0;  // Adler-32
    for (uint8_t c : raw) {
        a = (a + c) % 65521;
        b = (b + a) % 65521;
    }
    detail::putBE32(z, b << 16 | a);

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<uint8_t> ihdr;
    detail::putBE32(ihdr, width);
    detail::putBE32(ihdr, height);
    ihdr.insert(ihdr.end(), {uint8_t(depth), 0, 0, 0, 0});  // depth, gray, deflate, filter 0, no interlace
    detail::chunk(png, "IHDR", ihdr);
    detail::chunk(png, "IDAT", z);
    detail::chunk(png, "IEND", {});
    return png;
}

// The pattern as a width x height gray PNG of bit depth 16 or 8 (8: texels / 257,
// rounded).
inline std::vector<uint8_t> patternPng(uint32_t width, uint32_t height, int depth = 16) {
    std::vector<uint16_t> texels(size_t(width) * height);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const uint16_t t = patternTexel(x, y, width, height);
            texels[size_t(y) * width + x] = depth == 16 ? t : uint16_t((t + 128) / 257);
        }
    return grayPng(width, height, depth, texels);
}

}  // namespace lt::test
