// lt::bakeDisplacement and lt::chooseDisplacementResolution: a gray image resampled
// into the per-face tiles with shared borders of the spec's "Displacement map"
// (asset.h's DisplacementMap). No I/O: the image arrives decoded (png_gray.cpp).
//
// 1. Edges are numbered in first-use order over the face corners (face 0 edges 0,
//    1, 2, face 1 ...; one number per unordered control-vertex pair): faceEdges.
// 2. Every face reads the image at every grid point of its tile, through its own
//    corner UVs. An interior sample belongs to one face and takes its reading; a
//    vertex or edge sample takes the mean of the readings of all faces that contain
//    it (seam welding). Sums run in double, in face order, so the result does not
//    depend on anything but the inputs.
// 3. Samples are rounded to 16 bits: q = floor(65535 * value + 1/2).
#include "looptess/tools/baker.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <vector>

namespace lt {
namespace {

bool validResolution(uint32_t r) { return r >= 1 && r <= 64 && (r & (r - 1)) == 0; }

// Step 1: faceEdges in first-use order; returns the edge count.
uint32_t numberEdges(const Asset& a, std::vector<uint32_t>& faceEdges) {
    std::unordered_map<uint64_t, uint32_t> ids;  // only looked up: its order never shows
    ids.reserve(a.faces.size());
    faceEdges.resize(a.faces.size());
    for (size_t k = 0; k < a.faces.size(); ++k) {
        const uint32_t x = a.faces[k], y = a.faces[k - k % 3 + (k + 1) % 3];
        const uint64_t key = uint64_t(std::min(x, y)) << 32 | std::max(x, y);
        faceEdges[k] = ids.emplace(key, uint32_t(ids.size())).first->second;
    }
    return uint32_t(ids.size());
}

// x reduced to [0, n) (repeat wrap), as an integer texel index and its fraction.
void wrapTexel(double x, uint32_t n, uint32_t& i0, uint32_t& i1, double& frac) {
    const double period = double(n);
    double m = x - period * std::floor(x / period);  // [0, n], n only by rounding
    double f = std::floor(m);
    if (!(f >= 0.0 && f < period)) f = 0.0;  // m == n (rounding), or NaN
    i0 = uint32_t(f);
    i1 = i0 + 1 == n ? 0 : i0 + 1;
    frac = m - f;
    if (!(frac >= 0.0 && frac <= 1.0)) frac = 0.0;
}

// The image at (u, v) (glTF convention: v down), bilinear between the four
// nearest texel centres, in texel units (0 .. 65535).
double bilinear(const GrayImage& im, double u, double v) {
    uint32_t x0, x1, y0, y1;
    double fx, fy;
    wrapTexel(u * im.width - 0.5, im.width, x0, x1, fx);
    wrapTexel(v * im.height - 0.5, im.height, y0, y1, fy);
    auto t = [&](uint32_t x, uint32_t y) { return double(im.texels[size_t(y) * im.width + x]); };
    const double top = (1.0 - fx) * t(x0, y0) + fx * t(x1, y0);
    const double bottom = (1.0 - fx) * t(x0, y1) + fx * t(x1, y1);
    return (1.0 - fy) * top + fy * bottom;
}

uint16_t quantize(double texelUnits) {
    const double q = std::floor(texelUnits + 0.5);
    return uint16_t(q <= 0.0 ? 0.0 : q >= 65535.0 ? 65535.0 : q);  // NaN -> 0
}

uint64_t sampleCount(const Asset& a, uint32_t R, uint32_t edges) {
    return displacementSampleCount(R, a.controlVertexCount(), a.faceCount(), edges);
}

}  // namespace

uint32_t chooseDisplacementResolution(const Asset& asset, const GrayImage& image) {
    const uint32_t faces = asset.faceCount();
    if (faces == 0 || asset.faceUVs.size() != 6 * size_t(faces) || image.texels.empty()) return 1;
    double area = 0;  // UV area of all faces, in texels
    for (uint32_t f = 0; f < faces; ++f) {
        const float* t = &asset.faceUVs[6 * size_t(f)];
        const double ax = double(t[2]) - t[0], ay = double(t[3]) - t[1];
        const double bx = double(t[4]) - t[0], by = double(t[5]) - t[1];
        const double a = 0.5 * std::fabs(ax * by - ay * bx);
        if (std::isfinite(a)) area += a;
    }
    const double perFace = area * double(image.width) * double(image.height) / faces;
    uint32_t R = 1;
    while (R < 64 && double(R) * R / 2 < perFace) R *= 2;
    std::vector<uint32_t> faceEdges;
    const uint32_t edges = numberEdges(asset, faceEdges);
    while (R > 1 && sampleCount(asset, R, edges) > kMaxDisplacementSamples) R /= 2;
    return R;
}

Status bakeDisplacement(const GrayImage& image, const DisplacementSettings& settings, Asset& asset,
                        const std::string& name) {
    const uint32_t faces = asset.faceCount(), vertices = asset.controlVertexCount();
    if (asset.faceUVs.empty())
        return Status::error(Status::BadInput, name +
                                                   ": a displacement map needs texture coordinates "
                                                   "(OBJ vt, glTF TEXCOORD_0); the mesh has none");
    if (asset.faceUVs.size() != 6 * size_t(faces) || asset.faces.size() != 3 * size_t(faces))
        return Status::error(Status::BadInput, name + ": the asset's faces or UVs are malformed");
    if (image.width == 0 || image.height == 0 || image.texels.size() != size_t(image.width) * image.height)
        return Status::error(Status::BadInput, name + ": the displacement map has no texels");
    if (!std::isfinite(settings.scale) || !std::isfinite(settings.bias))
        return Status::error(Status::Usage, name + ": the displacement scale and bias must be finite");
    const uint32_t R = settings.resolution ? settings.resolution : chooseDisplacementResolution(asset, image);
    if (!validResolution(R))
        return Status::error(Status::Usage, name + ": displacement resolution " + std::to_string(R) +
                                                " is not a power of two from 1 to 64");
    for (size_t k = 0; k < asset.faceUVs.size(); ++k)
        if (!std::isfinite(asset.faceUVs[k]))
            return Status::error(Status::BadInput, name + ": face " + std::to_string(k / 6) + " corner " +
                                                       std::to_string(k % 6 / 2) + " has a non-finite UV");

    DisplacementMap& map = asset.displacement;
    map = DisplacementMap{};
    const uint32_t edges = numberEdges(asset, map.faceEdges);
    const uint64_t total = sampleCount(asset, R, edges);
    if (total > kMaxDisplacementSamples)
        return Status::error(Status::Unsupported,
                             name + ": a displacement map of resolution " + std::to_string(R) + " has " +
                                 std::to_string(total) + " samples, more than the limit of " +
                                 std::to_string(kMaxDisplacementSamples) + " (choose a lower resolution)");
    map.resolution = R;
    map.scale = settings.scale;
    map.bias = settings.bias;
    map.values.assign(size_t(total), 0);

    // Shared samples: vertices [0, V) and edges [edgeBase, total) of `values`,
    // accumulated at border slot (index < V ? index : V + index - edgeBase).
    const uint64_t edgeBase = total - uint64_t(edges) * (R - 1);
    std::vector<double> sum(size_t(vertices + (total - edgeBase)), 0.0);
    std::vector<uint32_t> count(sum.size(), 0);
    for (uint32_t f = 0; f < faces; ++f) {
        const float* t = &asset.faceUVs[6 * size_t(f)];
        for (uint32_t j = 0; j <= R; ++j)
            for (uint32_t i = 0; i + j <= R; ++i) {
                const double w1 = double(i) / R, w2 = double(j) / R, w0 = double(R - i - j) / R;  // exact
                const double u = w0 * t[0] + w1 * t[2] + w2 * t[4];
                const double v = w0 * t[1] + w1 * t[3] + w2 * t[5];
                const double value = bilinear(image, u, v);
                const uint64_t index = displacementSample(asset, f, i, j);
                if (index >= vertices && index < edgeBase) {
                    map.values[size_t(index)] = quantize(value);
                } else {
                    const size_t slot = size_t(index < vertices ? index : vertices + (index - edgeBase));
                    sum[slot] += value;
                    ++count[slot];
                }
            }
    }
    for (size_t slot = 0; slot < sum.size(); ++slot) {  // unused control vertices keep 0
        const uint64_t index = slot < vertices ? slot : edgeBase + (slot - vertices);
        if (count[slot]) map.values[size_t(index)] = quantize(sum[slot] / count[slot]);
    }
    return Status::ok();
}

}  // namespace lt
