// baker/src/gltf_primitive.cpp -- readPrimitive (gltf_primitive.h).
#include "gltf_primitive.h"

#include "gltf_accessor.h"
#include "gltf_draco.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace lt::gltf {
namespace {

std::string str(uint64_t v) { return std::to_string(v); }

// Vertex attribute TEXCOORD_0 (into out.uvs) or NORMAL (out.normals) from its
// accessor, which must have `vertices` elements; left empty when absent.
Status readAttribute(const tinygltf::Model& model, const tinygltf::Primitive& p, Semantic semantic, bool quantized,
                     size_t vertices, const std::string& where, DecodeBudget& budget, Primitive& out) {
    const bool uv = semantic == Semantic::TexCoord;
    const std::string name = uv ? "TEXCOORD_0" : "NORMAL";
    std::vector<double>& values = uv ? out.uvs : out.normals;
    auto it = p.attributes.find(name);
    if (it == p.attributes.end()) return Status::ok();
    const std::string at = where + ".attributes." + name;
    const size_t components = uv ? 2 : 3;
    Status st = readAccessor(model, it->second, semantic, quantized, at, budget, values);
    if (st && values.size() / components != vertices)
        return badInput(at,
                        "count " + str(values.size() / components) + " differs from POSITION count " + str(vertices));
    return st;
}

// `corners` (indices, or 0 .. n-1) as a triangle list by `mode` (the header's table).
Status triangleList(int mode, std::vector<uint32_t>& corners, const std::string& where, std::vector<uint32_t>& out) {
    const size_t n = corners.size();
    if (mode == TINYGLTF_MODE_TRIANGLES || mode == -1) {
        if (n % 3 != 0) return badInput(where, str(n) + " corners is not a multiple of 3");
        out = std::move(corners);
        return Status::ok();
    }
    if (n < 3) return badInput(where, str(n) + " corners make no triangle");
    out.clear();
    out.reserve(3 * (n - 2));
    for (size_t i = 0; i + 2 < n; ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
            out.insert(out.end(), {corners[i], corners[i + 1 + i % 2], corners[i + 2 - i % 2]});
        else
            out.insert(out.end(), {corners[i + 1], corners[i + 2], corners[0]});
    }
    return Status::ok();
}

// JOINTS_n and WEIGHTS_n, set after set, into out.joints and out.weights; left empty
// when a set is incomplete or does not read (the attributes pass through as they are).
void readSkin(const tinygltf::Model& model, const tinygltf::Primitive& p, size_t vertices, DecodeBudget& budget,
              Primitive& out) {
    for (int n = 0;; ++n) {
        auto j = p.attributes.find("JOINTS_" + str(uint64_t(n))), w = p.attributes.find("WEIGHTS_" + str(uint64_t(n)));
        if (j == p.attributes.end() || w == p.attributes.end()) break;
        std::vector<double> joints, weights;
        if (!readAccessor(model, j->second, Semantic::Joints, false, "", budget, joints) ||
            !readAccessor(model, w->second, Semantic::Weights, false, "", budget, weights) ||
            joints.size() != 4 * vertices || weights.size() != 4 * vertices) {
            out.joints.clear();
            out.weights.clear();
            return;
        }
        out.joints.insert(out.joints.end(), joints.begin(), joints.end());
        out.weights.insert(out.weights.end(), weights.begin(), weights.end());
    }
}

Status readPlain(const tinygltf::Model& model, const tinygltf::Primitive& p, bool quantized, bool normals,
                 const std::string& where, DecodeBudget& budget, Primitive& out) {
    auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) return badInput(where, "has no POSITION attribute");
    Status st = readAccessor(model, pos->second, Semantic::Position, quantized, where + ".attributes.POSITION", budget,
                             out.positions);
    if (st) st = readAttribute(model, p, Semantic::TexCoord, quantized, out.vertexCount(), where, budget, out);
    if (st && normals) st = readAttribute(model, p, Semantic::Normal, quantized, out.vertexCount(), where, budget, out);
    if (!st) return st;
    const size_t vertices = out.vertexCount();
    std::vector<uint32_t> corners;
    if (p.indices < 0) {
        corners.resize(vertices);
        for (size_t i = 0; i < vertices; ++i) corners[i] = uint32_t(i);
    } else {
        const std::string at = where + ".indices";
        std::vector<double> indices;
        if (!(st = readAccessor(model, p.indices, Semantic::Indices, false, at, budget, indices))) return st;
        corners.resize(indices.size());
        for (size_t i = 0; i < indices.size(); ++i) {
            if (indices[i] >= double(vertices))
                return badInput(at, "index " + str(uint64_t(indices[i])) + " (entry " + str(i) + ") >= vertex count " +
                                        str(vertices));
            corners[i] = uint32_t(indices[i]);
        }
    }
    st = triangleList(p.mode, corners, where + (p.indices < 0 ? " (no indices)" : ".indices"), out.triangles);
    if (st) readSkin(model, p, vertices, budget, out);
    return st;
}

Status readDraco(const tinygltf::Model& model, const tinygltf::Primitive& p, const tinygltf::Value& ext, bool quantized,
                 bool normals, const std::string& where, DecodeBudget& budget, Primitive& out) {
    const std::string at = where + ".extensions.KHR_draco_mesh_compression";
    if (!ext.IsObject() || !ext.Get("bufferView").IsInt() || !ext.Get("attributes").IsObject())
        return badInput(at, "needs an integer bufferView and an attributes object");
    const tinygltf::Value& attributes = ext.Get("attributes");
    auto id = [&](const char* semantic) {
        const tinygltf::Value& v = attributes.Get(semantic);
        return v.IsInt() && v.Get<int>() >= 0 ? v.Get<int>() : attributes.Has(semantic) ? -2 : -1;
    };
    const int position = id("POSITION"), texcoord = id("TEXCOORD_0"), normal = normals ? id("NORMAL") : -1;
    if (position < 0 || texcoord == -2 || normal == -2)
        return badInput(at,
                        "attributes.POSITION is missing, or an attribute id is not a "
                        "non-negative integer");
    const uint8_t* bytes;
    size_t size;
    Status st = viewBytes(model, ext.Get("bufferView").Get<int>(), at, bytes, size);
    if (st) st = decodeDraco(bytes, size, position, texcoord, normal, at, budget, out);
    // TEXCOORD_0 and NORMAL outside the Draco payload (allowed by the extension) come
    // uncompressed.
    if (st && texcoord < 0)
        st = readAttribute(model, p, Semantic::TexCoord, quantized, out.vertexCount(), where, budget, out);
    if (st && normals && normal < 0)
        st = readAttribute(model, p, Semantic::Normal, quantized, out.vertexCount(), where, budget, out);
    return st;
}

}  // namespace

bool sameInfluences(const Primitive& a, size_t va, const Primitive& b, size_t vb) {
    if (a.joints.empty() && b.joints.empty()) return true;  // no skin: nothing to compare
    auto influences = [](const Primitive& p, size_t v) {
        std::vector<std::pair<double, double>> out;  // (joint, weight), by joint
        const size_t vertices = p.vertexCount();
        for (size_t set = 0; vertices && set < p.joints.size() / (4 * vertices); ++set)
            for (size_t c = 0; c < 4; ++c) {
                const size_t at = (set * vertices + v) * 4 + c;
                if (p.weights[at] != 0) out.emplace_back(p.joints[at], p.weights[at]);
            }
        std::sort(out.begin(), out.end());
        size_t kept = 0;
        for (size_t i = 0; i < out.size(); ++i) {
            if (kept && out[kept - 1].first == out[i].first)
                out[kept - 1].second += out[i].second;
            else
                out[kept++] = out[i];
        }
        out.resize(kept);
        return out;
    };
    const auto x = influences(a, va), y = influences(b, vb);
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i)
        if (x[i].first != y[i].first || std::fabs(x[i].second - y[i].second) > 1e-4) return false;
    return true;
}

bool isTriangles(const tinygltf::Primitive& p) {
    return p.mode == -1 || p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
           p.mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

Status readPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& p, bool quantized, bool normals,
                     const std::string& where, DecodeBudget& budget, Primitive& out) {
    auto draco = p.extensions.find("KHR_draco_mesh_compression");
    if (draco != p.extensions.end()) return readDraco(model, p, draco->second, quantized, normals, where, budget, out);
    return readPlain(model, p, quantized, normals, where, budget, out);
}

}  // namespace lt::gltf
