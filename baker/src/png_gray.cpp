// lt::decodeGrayPng: a grayscale PNG from memory into a GrayImage (stb_image does
// the decoding; libstb-dev). The PNG header is read here first, so a map of the
// wrong kind is refused by name before anything is decompressed.
#include "looptess/tools/baker.h"

#include <stb_image.h>

#include <climits>
#include <cstring>
#include <string>

namespace lt {
namespace {

uint32_t bigEndian32(const uint8_t* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

const char* colorTypeName(int type) {
    switch (type) {
    case 2: return "RGB";
    case 3: return "palette";
    case 6: return "RGBA";
    default: return "unknown";
    }
}

}  // namespace

Status decodeGrayPng(const uint8_t* data, size_t size, const std::string& name, GrayImage& image) {
    static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    image = GrayImage{};
    // Signature (8), IHDR chunk: length (4), "IHDR" (4), width, height (4 + 4),
    // bit depth (1), colour type (1), ...
    if (!data || size < 8 || std::memcmp(data, kSignature, 8) != 0)
        return Status::error(Status::BadInput,
                             name + ": not a PNG file (a displacement map is an 8- or 16-bit grayscale PNG)");
    if (size < 33 || std::memcmp(data + 12, "IHDR", 4) != 0)
        return Status::error(Status::BadInput, name + ": truncated PNG (no IHDR chunk)");
    const uint32_t width = bigEndian32(data + 16), height = bigEndian32(data + 20);
    const int depth = data[24], colorType = data[25];
    if (colorType != 0 && colorType != 4)
        return Status::error(Status::Unsupported,
                             name + ": a " + colorTypeName(colorType) +
                                 " PNG; a displacement map must be grayscale (8- or 16-bit gray, optionally with "
                                 "alpha): convert it first, e.g. keep one channel");
    if (width == 0 || height == 0)
        return Status::error(Status::BadInput,
                             name + ": PNG of " + std::to_string(width) + "x" + std::to_string(height) + " texels");
    if (uint64_t(width) * height > kMaxDisplacementMapTexels)
        return Status::error(Status::BadInput, name + ": " + std::to_string(width) + "x" + std::to_string(height) +
                                                   " texels, more than the limit of " +
                                                   std::to_string(kMaxDisplacementMapTexels));
    if (size > size_t(INT_MAX))
        return Status::error(Status::BadInput, name + ": " + std::to_string(size) + " bytes is too large for a PNG");

    int w = 0, h = 0, channels = 0;
    // One channel requested: gray + alpha drops the alpha; 8-bit gray is widened
    // to 16 bits as q * 257 (so q / 255 == q * 257 / 65535 exactly).
    stbi_us* texels = stbi_load_16_from_memory(data, int(size), &w, &h, &channels, 1);
    if (!texels) {
        const char* why = stbi_failure_reason();
        return Status::error(Status::BadInput,
                             name + ": cannot decode the PNG (" + (why ? why : "unknown error") + ")");
    }
    if (uint32_t(w) != width || uint32_t(h) != height) {
        stbi_image_free(texels);
        return Status::error(Status::BadInput, name + ": the PNG decodes to a size its header does not state");
    }
    image.width = width;
    image.height = height;
    image.bitDepth = uint32_t(depth);
    image.texels.assign(texels, texels + size_t(width) * height);
    stbi_image_free(texels);
    return Status::ok();
}

}  // namespace lt
