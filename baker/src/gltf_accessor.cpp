// baker/src/gltf_accessor.cpp -- checked bufferView and accessor reads. See gltf_accessor.h.
#include "gltf_accessor.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>

namespace lt::gltf {
namespace {

template <class T>
std::string str(T v) {
    return std::to_string(v);
}

// "<where>: accessor N <what>", the form of every accessor message.
Status failAt(const std::string& at, const std::string& what) {
    return Status::error(Status::BadInput, at + " " + what);
}

enum : int {
    kByte = TINYGLTF_COMPONENT_TYPE_BYTE,
    kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
    kShort = TINYGLTF_COMPONENT_TYPE_SHORT,
    kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
    kUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
    kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT,
};

// Bytes per component of the types glTF allows for vertex data and indices; 0 otherwise.
size_t componentSize(int type) {
    switch (type) {
    case kByte:
    case kUByte: return 1;
    case kShort:
    case kUShort: return 2;
    case kUInt:
    case kFloat: return 4;
    default: return 0;
    }
}

std::string typeName(int type) {
    if (type == TINYGLTF_TYPE_SCALAR) return "SCALAR";
    if (type >= 2 && type <= 4) return "VEC" + str(type);
    if (type >= 32 + 2 && type <= 32 + 4) return "MAT" + str(type - 32);
    return str(type);
}

const char* semanticName(Semantic s) {
    switch (s) {
    case Semantic::Position: return "POSITION";
    case Semantic::TexCoord: return "TEXCOORD_0";
    case Semantic::Normal: return "NORMAL";
    case Semantic::Indices: return "indices";
    case Semantic::Joints: return "JOINTS_n";
    case Semantic::Weights: return "WEIGHTS_n";
    }
    return "";
}

bool formatAllowed(Semantic s, int type, bool normalized, bool quantized) {
    const bool small = type == kByte || type == kUByte || type == kShort || type == kUShort;
    switch (s) {
    case Semantic::Position: return (type == kFloat && !normalized) || (quantized && small);
    case Semantic::TexCoord:
        if (type == kFloat) return !normalized;
        if (type == kUByte || type == kUShort) return normalized || quantized;
        return quantized && small;
    case Semantic::Normal:  // KHR_mesh_quantization: normalized signed bytes or shorts
        return (type == kFloat && !normalized) || (quantized && normalized && (type == kByte || type == kShort));
    case Semantic::Indices: return !normalized && (type == kUByte || type == kUShort || type == kUInt);
    case Semantic::Joints: return !normalized && (type == kUByte || type == kUShort);
    case Semantic::Weights: return type == kFloat ? !normalized : normalized && (type == kUByte || type == kUShort);
    }
    return false;
}

// One component at `p` (unaligned), normalized integers mapped as glTF 2.0 section
// 3.11 specifies (signed: max(c / max, -1)).
double component(const uint8_t* p, int type, bool normalized) {
    switch (type) {
    case kByte: {
        int8_t v;
        std::memcpy(&v, p, 1);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUByte: return normalized ? p[0] / 255.0 : p[0];
    case kShort: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUShort: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case kUInt: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    default: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    }
}

// Overwrites the elements a sparse accessor names. `at` is "<where>: accessor N".
Status applySparse(const tinygltf::Model& model, const tinygltf::Accessor& a, size_t comps, const std::string& at,
                   std::vector<double>& out) {
    const auto& sp = a.sparse;
    const size_t csize = componentSize(a.componentType), elem = csize * comps;
    const size_t isize = componentSize(sp.indices.componentType);
    if (sp.count < 1 || size_t(sp.count) > a.count)
        return failAt(at, "sparse count " + str(sp.count) + " is not in [1, " + str(a.count) + "]");
    if (!formatAllowed(Semantic::Indices, sp.indices.componentType, false, false))
        return failAt(at, "sparse indices componentType " + str(sp.indices.componentType) +
                              " is not an unsigned byte, short or int");
    if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) return failAt(at, "sparse byteOffset is negative");
    const uint8_t *ib, *vb;
    size_t isz, vsz;
    Status st = viewBytes(model, sp.indices.bufferView, at + " sparse indices", ib, isz);
    if (st) st = viewBytes(model, sp.values.bufferView, at + " sparse values", vb, vsz);
    if (!st) return st;
    const uint64_t n = uint64_t(sp.count);
    if (uint64_t(sp.indices.byteOffset) + n * isize > isz)
        return failAt(at, "sparse indices (count " + str(n) + ") overrun bufferView " + str(sp.indices.bufferView));
    if (uint64_t(sp.values.byteOffset) + n * elem > vsz)
        return failAt(at, "sparse values (count " + str(n) + ") overrun bufferView " + str(sp.values.bufferView));
    ib += sp.indices.byteOffset;
    vb += sp.values.byteOffset;
    uint64_t prev = 0;
    for (size_t k = 0; k < n; ++k) {
        const uint64_t i = uint64_t(component(ib + k * isize, sp.indices.componentType, false));
        if (i >= a.count)
            return failAt(at, "sparse index " + str(i) + " (entry " + str(k) + ") >= count " + str(a.count));
        if (k > 0 && i <= prev) return failAt(at, "sparse indices are not strictly increasing at entry " + str(k));
        prev = i;
        for (size_t c = 0; c < comps; ++c)
            out[i * comps + c] = component(vb + k * elem + c * csize, a.componentType, a.normalized);
    }
    return Status::ok();
}

}  // namespace

Status viewBytes(const tinygltf::Model& model, int view, const std::string& where, const uint8_t*& data, size_t& size) {
    if (view < 0 || size_t(view) >= model.bufferViews.size())
        return badInput(
            where, "bufferView " + str(view) + " does not exist (" + str(model.bufferViews.size()) + " bufferViews)");
    const tinygltf::BufferView& v = model.bufferViews[size_t(view)];
    if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size())
        return badInput(where, "bufferView " + str(view) + ": buffer " + str(v.buffer) + " does not exist (" +
                                   str(model.buffers.size()) + " buffers)");
    const std::vector<unsigned char>& b = model.buffers[size_t(v.buffer)].data;
    if (v.byteOffset > b.size() || v.byteLength > b.size() - v.byteOffset)
        return badInput(where, "bufferView " + str(view) + " (byteOffset " + str(v.byteOffset) + ", byteLength " +
                                   str(v.byteLength) + ") overruns buffer " + str(v.buffer) + " (" + str(b.size()) +
                                   " bytes)");
    data = b.data() + v.byteOffset;
    size = v.byteLength;
    return Status::ok();
}

Status readAccessor(const tinygltf::Model& model, int index, Semantic semantic, bool quantized,
                    const std::string& where, DecodeBudget& budget, std::vector<double>& out) {
    if (index < 0 || size_t(index) >= model.accessors.size())
        return badInput(where,
                        "accessor " + str(index) + " does not exist (" + str(model.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    const std::string at = where + ": accessor " + str(index);
    const bool skin = semantic == Semantic::Joints || semantic == Semantic::Weights;
    const size_t comps = skin                                                             ? 4
                         : semantic == Semantic::Position || semantic == Semantic::Normal ? 3
                         : semantic == Semantic::TexCoord                                 ? 2
                                                                                          : 1;
    const int type = int(comps == 1 ? TINYGLTF_TYPE_SCALAR : comps);  // TINYGLTF_TYPE_VECn is n
    if (a.type != type)
        return failAt(at,
                      "type " + typeName(a.type) + " is not " + typeName(type) + " (" + semanticName(semantic) + ")");
    if (!formatAllowed(semantic, a.componentType, a.normalized, quantized))
        return failAt(at, "componentType " + str(a.componentType) + (a.normalized ? " normalized" : "") +
                              " is not allowed for " + semanticName(semantic) +
                              (quantized ? "" : " (without KHR_mesh_quantization)"));
    if (a.count == 0) return failAt(at, "count is 0");
    if (a.count > budget.maxElements())
        return failAt(at, "count " + str(a.count) + " is more than the limit of " + str(budget.maxElements()) +
                              " elements (3 per face of the face limit; raise it with --max-faces)");
    if (!budget.take(a.count)) return failAt(at, "count " + str(a.count) + ": " + budget.exhausted());
    const size_t csize = componentSize(a.componentType), elem = csize * comps;
    // Every byte range is checked before `out` is sized by the count the file declares.
    const uint8_t* bytes = nullptr;
    size_t stride = elem;
    if (a.bufferView >= 0) {
        size_t size;
        Status st = viewBytes(model, a.bufferView, at, bytes, size);
        if (!st) return st;
        const size_t declared = model.bufferViews[size_t(a.bufferView)].byteStride;
        if (declared && (declared < elem || declared > 252 || declared % 4 != 0))
            return failAt(at, "bufferView " + str(a.bufferView) + " byteStride " + str(declared) + " is invalid for " +
                                  str(elem) + "-byte elements");
        // glTF 2.0 "Data Alignment": misaligned values are another layout's bytes (a
        // file off by one byte read as floats is noise, not a mesh).
        const uint64_t inBuffer = uint64_t(a.byteOffset) + model.bufferViews[size_t(a.bufferView)].byteOffset;
        if (a.byteOffset % csize != 0 || inBuffer % csize != 0)
            return failAt(at, "byteOffset " + str(a.byteOffset) + " (" + str(inBuffer) +
                                  " in its buffer) is not a multiple of the component size " + str(csize));
        stride = declared ? declared : elem;
        const uint64_t need = uint64_t(a.byteOffset) + uint64_t(stride) * (a.count - 1) + elem;
        if (need > size)
            return failAt(at, "count " + str(a.count) + " overruns bufferView " + str(a.bufferView) + " (byteOffset " +
                                  str(a.byteOffset) + " + stride " + str(stride) + " x " + str(a.count - 1) + " + " +
                                  str(elem) + " > byteLength " + str(size) + ")");
        bytes += a.byteOffset;
    } else if (semantic == Semantic::Indices) {
        return failAt(at, "has no bufferView");
    }
    // Without a bufferView the values are zeros (plus sparse ones): the count is bounded
    // by the limits above, not by bytes in the file.
    out.assign(a.count * comps, 0.0);
    if (bytes)
        for (size_t i = 0; i < a.count; ++i)
            for (size_t c = 0; c < comps; ++c)
                out[i * comps + c] = component(bytes + i * stride + c * csize, a.componentType, a.normalized);
    return a.sparse.isSparse ? applySparse(model, a, comps, at, out) : Status::ok();
}

}  // namespace lt::gltf
