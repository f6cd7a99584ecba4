// formats/src/glb_document.h -- the glTF side of reading a GLB (rules 4 to 7): the
// parsed JSON document, its one buffer, JSON helpers that fail with a rule number,
// and accessors resolved and range-checked before anything is decoded. The
// extension's own rules are glb_read.cpp's (class Reader derives from this).
#pragma once

#include "layout.h"
#include "stream.h"

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <string>
#include <unordered_map>
#include <vector>

namespace lt::fmt {

using Json = nlohmann::json;

inline constexpr uint64_t kMaxJsonInteger = uint64_t(1) << 53;

inline std::string str(uint64_t v) { return std::to_string(v); }

inline constexpr uint64_t kNoView = ~uint64_t(0);

// A surface's compressed stream (rule 46): where its bytes are in the BIN chunk,
// its accessors' segments and, once decodeStreams ran, its decoded bytes.
struct Stream {
    std::string path;  // the compression object's JSON path
    uint64_t bufferView = 0, offset = 0, length = 0, decoded = 0;
    std::vector<Segment> segments;
    StreamBytes data;  // decodedBytes, once decoded
};

// A resolved accessor: offset of element 0 in the BIN chunk (stream 0) or in
// decoded stream `stream - 1`, and the element layout.
struct View {
    uint64_t index = 0, bufferView = 0;  // bufferView: kNoView for a stream's accessor
    uint64_t offset = 0, count = 0, stride = 0;
    int componentType = 0, components = 0;
    bool viewHasStride = false;
    uint32_t stream = 0;
    uint64_t byteSize() const { return (count - 1) * stride + uint64_t(componentSize(componentType)) * components; }
};

class GlbDocument {
protected:
    explicit GlbDocument(const std::string& name) : name_(name) {}

    const std::string& name_;
    Status status_;
    Json doc_;
    const uint8_t* bin_ = nullptr;
    uint64_t binLength_ = 0, bufferLength_ = 0;
    std::vector<Stream> streams_;
    // Accessors listed by a compression object -> (stream + 1, segment offset).
    std::unordered_map<uint64_t, std::pair<uint32_t, uint64_t>> streamed_;

    const uint8_t* base(const View& v) const { return v.stream ? streams_[v.stream - 1].data.get() : bin_; }

    bool fail(const std::string& path, int rule, const std::string& what) {
        if (status_) status_ = ruleError(name_, path, rule, what);
        return false;
    }

    // --- JSON helpers -------------------------------------------------------------
    static const Json* member(const Json& obj, const char* key) {
        if (!obj.is_object()) return nullptr;
        auto it = obj.find(key);
        return it == obj.end() ? nullptr : &*it;
    }

    // Optional non-negative integer `key` of `obj` (absent: `out` = `dflt`).
    bool uintAt(const Json& obj, const char* key, const std::string& path, int rule, uint64_t max, uint64_t& out,
                bool required, uint64_t dflt = 0) {
        const Json* v = member(obj, key);
        if (!v) {
            if (required) return fail(path, rule, "required property '" + std::string(key) + "' is missing");
            out = dflt;
            return true;
        }
        if (v->is_number_unsigned())
            out = v->get<uint64_t>();
        else if (v->is_number_integer())
            return fail(path + "." + key, rule, "is negative");
        else
            return fail(path + "." + key, rule, "is not an integer");
        if (out > max) return fail(path + "." + key, rule, str(out) + " is greater than " + str(max));
        return true;
    }

    const Json* arrayAt(const Json& obj, const char* key) {
        const Json* v = member(obj, key);
        return v && v->is_array() ? v : nullptr;
    }

    size_t arraySize(const char* key) {
        const Json* a = arrayAt(doc_, key);
        return a ? a->size() : 0;
    }

    // --- rule 4: one self-contained buffer -----------------------------------------
    bool buffer() {
        const Json* buffers = member(doc_, "buffers");
        if (!buffers || !buffers->is_array() || buffers->size() != 1 || !(*buffers)[0].is_object())
            return fail("buffers", kRuleSelfContained, "expected exactly one buffer (the GLB BIN chunk)");
        if (member((*buffers)[0], "uri")) return fail("buffers[0].uri", kRuleSelfContained, "URIs are not allowed");
        if (!uintAt((*buffers)[0], "byteLength", "buffers[0]", kRuleSelfContained, kMaxJsonInteger, bufferLength_,
                    true))
            return false;
        if (!bin_ || bufferLength_ > binLength_)
            return fail("buffers[0].byteLength", kRuleSelfContained,
                        str(bufferLength_) + " exceeds the BIN chunk's " + str(binLength_) + " bytes");
        if (const Json* images = arrayAt(doc_, "images"))
            for (size_t i = 0; i < images->size(); ++i)
                if (member((*images)[i], "uri"))
                    return fail("images[" + str(i) + "].uri", kRuleSelfContained, "URIs are not allowed");
        return true;
    }

    // --- rules 5, 6, 7: resolve an accessor of the form (`types`, `components`) ------
    // `inStream`: the accessor may be one a compression object lists (the
    // extension's own accessors); a cage primitive's never may (rule 46).
    // `normalized`: unsigned integer components must be normalized (a cage
    // primitive's TEXCOORD_1 and COLOR_0, glTF's forms); elsewhere none may be.
    bool resolve(uint64_t index, const std::string& user, const int* types, int components, View& out,
                 bool inStream = false, bool normalized = false) {
        const std::string ap = "accessors[" + str(index) + "]";
        const Json* accessors = arrayAt(doc_, "accessors");
        if (!accessors || index >= accessors->size() || !(*accessors)[index].is_object())
            return fail(user, kRuleAccessor, "accessor " + str(index) + " does not exist");
        const Json& acc = (*accessors)[index];
        if (member(acc, "sparse")) return fail(ap, kRuleAccessor, "sparse accessors are not allowed");
        const Json* norm = member(acc, "normalized");
        const bool isNormalized = norm && norm->is_boolean() && norm->get<bool>();
        if (norm && !(norm->is_boolean() && (!isNormalized || normalized)))
            return fail(ap, kRuleAccessor, "normalized accessors are not allowed");
        uint64_t ct, count;
        int actual;
        if (!header(acc, ap, ct, count, actual) || !form(index, int(ct), actual, user, types, components)) return false;
        if (normalized && ct != kF32 && !isNormalized)
            return fail(ap, kRuleAccessorForm, "integer components of " + user + " must be normalized");
        const int csize = componentSize(int(ct));
        const auto listed = streamed_.find(index);
        if (listed != streamed_.end() && !inStream)
            return fail(user, kRuleCompression,
                        "accessor " + str(index) + " is in a compressed stream; the cage is never compressed");
        if (listed != streamed_.end()) {  // rule 46 checked its form
            out = View{index,  kNoView, listed->second.second, count, uint64_t(csize) * actual, int(ct),
                       actual, false,   listed->second.first};
            return true;
        }
        uint64_t bv, accOffset;
        if (!uintAt(acc, "bufferView", ap, kRuleAccessor, arraySize("bufferViews"), bv, true) ||
            !uintAt(acc, "byteOffset", ap, kRuleAccessor, kMaxJsonInteger, accOffset, false))
            return false;
        if (bv == arraySize("bufferViews")) return fail(ap + ".bufferView", kRuleAccessor, "no such bufferView");
        const std::string vp = "bufferViews[" + str(bv) + "]";
        uint64_t viewOffset, viewLength, stride;
        if (!bufferView(bv, viewOffset, viewLength, stride)) return false;
        const uint64_t elemSize = uint64_t(csize) * actual;
        out.viewHasStride = member((*arrayAt(doc_, "bufferViews"))[bv], "byteStride") != nullptr;
        if (!out.viewHasStride) stride = elemSize;
        if (stride < elemSize || stride % csize != 0)
            return fail(
                vp + ".byteStride", kRuleBufferView,
                str(stride) + " does not fit accessor " + str(index) + "'s " + str(elemSize) + "-byte elements");
        out = View{index, bv, viewOffset + accOffset, count, stride, int(ct), actual, out.viewHasStride, 0};
        if (accOffset > viewLength || out.byteSize() > viewLength - accOffset)
            return fail(ap, kRuleAccessor,
                        "byteOffset " + str(accOffset) + " + " + str(out.byteSize()) + " bytes exceed bufferView " +
                            str(bv) + "'s byteLength " + str(viewLength));
        if (out.offset % csize != 0)
            return fail(ap, kRuleAccessor, "data offset " + str(out.offset) + " is not a multiple of " + str(csize));
        return true;
    }

    // Rule 5 for bufferView `bv` (< the bufferView count): its range in buffer 0 and
    // its byteStride (0 when absent).
    bool bufferView(uint64_t bv, uint64_t& offset, uint64_t& length, uint64_t& stride) {
        const std::string vp = "bufferViews[" + str(bv) + "]";
        const Json& view = (*arrayAt(doc_, "bufferViews"))[bv];
        uint64_t buffer;
        if (!view.is_object()) return fail(vp, kRuleBufferView, "is not an object");
        if (!uintAt(view, "buffer", vp, kRuleBufferView, 0, buffer, true) ||
            !uintAt(view, "byteOffset", vp, kRuleBufferView, kMaxJsonInteger, offset, false) ||
            !uintAt(view, "byteLength", vp, kRuleBufferView, kMaxJsonInteger, length, true) ||
            !uintAt(view, "byteStride", vp, kRuleBufferView, 252, stride, false))
            return false;
        if (length == 0) return fail(vp + ".byteLength", kRuleBufferView, "is 0");
        if (offset + length > bufferLength_)
            return fail(vp, kRuleBufferView,
                        "bytes [" + str(offset) + ", " + str(offset + length) + ") exceed buffer 0's " +
                            str(bufferLength_) + " bytes");
        return true;
    }

    // Rule 6 without the bufferView: componentType, count and type of accessor `acc`.
    bool header(const Json& acc, const std::string& ap, uint64_t& ct, uint64_t& count, int& components) {
        if (!uintAt(acc, "componentType", ap, kRuleAccessor, 5126, ct, true) ||
            !uintAt(acc, "count", ap, kRuleAccessor, kMaxJsonInteger, count, true))
            return false;
        if (componentSize(int(ct)) == 0)
            return fail(ap + ".componentType", kRuleAccessor, str(ct) + " is not a glTF componentType");
        if (count == 0) return fail(ap + ".count", kRuleAccessor, "is 0");
        const Json* type = member(acc, "type");
        const std::string typeName = type && type->is_string() ? type->get<std::string>() : "";
        components = 0;
        for (int c = 1; c <= 4; ++c)
            if (typeName == accessorTypeName(c)) components = c;
        if (components == 0) return fail(ap + ".type", kRuleAccessor, "missing or not SCALAR/VEC2/VEC3/VEC4");
        return true;
    }

    // Rule 7: componentType one of `types` (zero-terminated) and `components`.
    bool form(uint64_t index, int componentType, int actual, const std::string& user, const int* types,
              int components) {
        bool typeOk = false;
        std::string expected;
        for (const int* t = types; *t; ++t) {
            typeOk = typeOk || componentType == *t;
            expected += (expected.empty() ? "" : " or ") + str(*t);
        }
        if (typeOk && actual == components) return true;
        return fail(user, kRuleAccessorForm,
                    "accessor " + str(index) + " is " + str(componentType) + " " + accessorTypeName(actual) +
                        ", expected " + expected + " " + accessorTypeName(components));
    }

    static const int* typesOf(Elem e) {
        static const int index[] = {kU16, kU32, 0}, small[] = {kU8, kU16, 0}, u8[] = {kU8, 0}, f32[] = {kF32, 0};
        switch (e) {
        case Elem::Index: return index;
        case Elem::Small: return small;
        case Elem::U8: return u8;
        case Elem::Float: return f32;
        }
        return f32;
    }

    // The values of a resolved accessor, when it is tightly packed (every accessor
    // the extension names is, rule 14).
    Packed packed(const View& v) const {
        return Packed{base(v) + v.offset, size_t(v.count) * size_t(v.components), v.componentType};
    }

    // Rule 9's TEXCOORD_1 (`sizes` {2}) or COLOR_0 ({3, 4}): absent, or float or
    // normalized unsigned byte / short with `vcount` elements, as floats (glTF: c / 255,
    // c / 65535) with `width` components (a missing fourth is 1).
    bool extraAttribute(const Json& prim, const char* key, const std::string& ap, std::initializer_list<int> sizes,
                        int width, uint64_t vcount, std::vector<float>& out) {
        const Json* attrs = member(prim, "attributes");
        if (!attrs || !member(*attrs, key)) return true;
        uint64_t index;
        if (!uintAt(*attrs, key, ap, kRuleFallbackPrimitive, kMaxJsonInteger, index, true)) return false;
        int components = *sizes.begin();  // the accessor's own type where it is one of `sizes`
        const Json* accessors = arrayAt(doc_, "accessors");
        if (accessors && index < accessors->size())
            if (const Json* type = member((*accessors)[index], "type"); type && type->is_string())
                for (int c : sizes)
                    if (type->get<std::string>() == accessorTypeName(c)) components = c;
        static const int forms[] = {kF32, kU8, kU16, 0};
        View v;
        const std::string user = ap + "." + key;
        if (!resolve(index, user, forms, components, v, false, true)) return false;
        if (v.count != vcount)
            return fail(user, kRuleFallbackPrimitive, str(v.count) + " elements, POSITION has " + str(vcount));
        std::vector<float> values;
        if (v.componentType == kF32) {
            this->values(v, values);
        } else {
            std::vector<uint32_t> raw;
            this->values(v, raw);
            const float scale = v.componentType == kU8 ? 255.0f : 65535.0f;
            values.resize(raw.size());
            for (size_t i = 0; i < raw.size(); ++i) values[i] = float(raw[i]) / scale;
        }
        out.assign(size_t(vcount) * size_t(width), 1.0f);
        for (size_t e = 0; e < size_t(vcount); ++e)
            std::copy_n(&values[e * size_t(components)], components, &out[e * size_t(width)]);
        return true;
    }

    // Any resolved accessor's values (the fallback primitive's may be strided).
    template <typename T>
    void values(const View& v, std::vector<T>& out) const {
        const uint64_t elemSize = uint64_t(componentSize(v.componentType)) * uint64_t(v.components);
        if (v.stride == elemSize) return loadValues(out, packed(v));
        std::vector<T> element;
        out.clear();
        out.reserve(size_t(v.count) * size_t(v.components));
        for (uint64_t e = 0; e < v.count; ++e) {
            loadValues(element, Packed{base(v) + v.offset + e * v.stride, size_t(v.components), v.componentType});
            out.insert(out.end(), element.begin(), element.end());
        }
    }
};

}  // namespace lt::fmt
