// formats/src/glb_read.cpp -- lt::readAssetGlb: untrusted GLB bytes -> Asset.
//
// Order of work, so that nothing is allocated before the file justifies it:
//   1. GLB header and chunks (rules 1, 2), JSON nesting pre-scan and parse (3):
//      glb_container.cpp; the one buffer (4);
//   2. the primitive carrying the extension (8) and the extension object (12, 13);
//      every accessor it names is resolved and range-checked (5, 6, 7) and the
//      accessors must be pairwise disjoint (14) -- so all decoded tables together
//      are at most 4x the BIN chunk;
//   3. decode the fallback primitive (9), rebuild the control mesh (10, 11:
//      control_mesh.cpp) and
//      the tables (15) -- applying the validator's per-patch checks on the way --,
//      the displacement map (36) and edit values (40), then validate the tables (16..44).
#include "glb_container.h"
#include "layout.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace lt {
namespace {

using namespace fmt;
using Json = nlohmann::json;

constexpr uint64_t kMaxJsonInteger = uint64_t(1) << 53;

std::string str(uint64_t v) { return std::to_string(v); }
size_t firstNotBelow(const std::vector<uint32_t>& v, uint64_t limit);

// A resolved accessor: absolute BIN offset of element 0 and the element layout.
struct View {
    uint64_t index = 0, bufferView = 0;
    uint64_t offset = 0, count = 0, stride = 0;
    int componentType = 0, components = 0;
    bool viewHasStride = false;
    uint64_t byteSize() const { return (count - 1) * stride + uint64_t(componentSize(componentType)) * components; }
};

// Ref::prop of the accessors that are not level rows.
constexpr int kPropControlVertex = -1, kPropFaceEdges = -2, kPropValues = -3, kPropEditValues = -4;

// An accessor named by the extension: controlVertex, a level row (prop >= 0, a
// Row), one of the displacement map's two or editValues.
struct Ref {
    size_t level = 0;
    int prop = -1;
    std::string path;
    View view;
};

class Reader {
public:
    Reader(const uint8_t* data, size_t size, const std::string& name) : data_(data), size_(size), name_(name) {}

    Status run(Asset& out) {
        GlbContainer container;
        status_ = readGlbContainer(data_, size_, name_, container);
        if (!status_) return status_;
        doc_ = std::move(container.json);
        bin_ = container.bin;
        binLength_ = container.binLength;
        if (buffer() && findPrimitive() && extension() && disjoint() && primitive() &&
            tables() && displacementTables() && editTables()) {
            Status st = validateTables(asset_, name_, patchesChecked_);
            if (st) out = std::move(asset_);
            return st;
        }
        return status_;
    }

private:
    const uint8_t* data_;
    size_t size_;
    const std::string& name_;
    Status status_;
    Asset asset_;
    Json doc_;
    const uint8_t* bin_ = nullptr;
    uint64_t binLength_ = 0, bufferLength_ = 0;
    const Json* prim_ = nullptr;
    const Json* ext_ = nullptr;
    std::string primPath_, extPath_;
    std::vector<Ref> refs_;
    bool patchesChecked_ = true;   // every decoded patch passed regularOk / irregularOk

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
    bool uintAt(const Json& obj, const char* key, const std::string& path, int rule, uint64_t max,
                uint64_t& out, bool required, uint64_t dflt = 0) {
        const Json* v = member(obj, key);
        if (!v) {
            if (required) return fail(path, rule, "required property '" + std::string(key) + "' is missing");
            out = dflt;
            return true;
        }
        if (v->is_number_unsigned()) out = v->get<uint64_t>();
        else if (v->is_number_integer()) return fail(path + "." + key, rule, "is negative");
        else return fail(path + "." + key, rule, "is not an integer");
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

    // Accessor property `key` of `obj` (at `path`; its value checked under `rule`),
    // resolved with form (`types`, `components`) and added to refs_.
    bool accessorRef(const Json& obj, const char* key, const std::string& path, int rule, size_t level, int prop,
                     const int* types, int components) {
        Ref r;
        r.level = level;
        r.prop = prop;
        r.path = path + "." + key;
        uint64_t index;
        if (!uintAt(obj, key, path, rule, kMaxJsonInteger, index, true) ||
            !resolve(index, r.path, types, components, r.view))
            return false;
        refs_.push_back(std::move(r));
        return true;
    }

    // --- rule 4: one self-contained buffer -----------------------------------------
    bool buffer() {
        const Json* buffers = member(doc_, "buffers");
        if (!buffers || !buffers->is_array() || buffers->size() != 1 || !(*buffers)[0].is_object())
            return fail("buffers", kRuleSelfContained, "expected exactly one buffer (the GLB BIN chunk)");
        if (member((*buffers)[0], "uri")) return fail("buffers[0].uri", kRuleSelfContained, "URIs are not allowed");
        if (!uintAt((*buffers)[0], "byteLength", "buffers[0]", kRuleSelfContained, kMaxJsonInteger, bufferLength_, true))
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
    bool resolve(uint64_t index, const std::string& user, const int* types, int components, View& out) {
        const std::string ap = "accessors[" + str(index) + "]";
        const Json* accessors = arrayAt(doc_, "accessors");
        if (!accessors || index >= accessors->size() || !(*accessors)[index].is_object())
            return fail(user, kRuleAccessor, "accessor " + str(index) + " does not exist");
        const Json& acc = (*accessors)[index];
        if (member(acc, "sparse")) return fail(ap, kRuleAccessor, "sparse accessors are not allowed");
        const Json* normalized = member(acc, "normalized");
        if (normalized && !(normalized->is_boolean() && !normalized->get<bool>()))
            return fail(ap, kRuleAccessor, "normalized accessors are not allowed");
        uint64_t bv, ct, count, accOffset;
        if (!uintAt(acc, "bufferView", ap, kRuleAccessor, arraySize("bufferViews"), bv, true) ||
            !uintAt(acc, "componentType", ap, kRuleAccessor, 5126, ct, true) ||
            !uintAt(acc, "count", ap, kRuleAccessor, kMaxJsonInteger, count, true) ||
            !uintAt(acc, "byteOffset", ap, kRuleAccessor, kMaxJsonInteger, accOffset, false))
            return false;
        if (bv == arraySize("bufferViews")) return fail(ap + ".bufferView", kRuleAccessor, "no such bufferView");
        const int csize = componentSize(int(ct));
        if (csize == 0) return fail(ap + ".componentType", kRuleAccessor, str(ct) + " is not a glTF componentType");
        if (count == 0) return fail(ap + ".count", kRuleAccessor, "is 0");
        const Json* type = member(acc, "type");
        const std::string typeName = type && type->is_string() ? type->get<std::string>() : "";
        int actual = 0;
        for (int c = 1; c <= 4; ++c)
            if (typeName == accessorTypeName(c)) actual = c;
        if (actual == 0) return fail(ap + ".type", kRuleAccessor, "missing or not SCALAR/VEC2/VEC3/VEC4");
        if (!form(index, int(ct), actual, user, types, components)) return false;

        const std::string vp = "bufferViews[" + str(bv) + "]";
        const Json& view = (*arrayAt(doc_, "bufferViews"))[bv];
        uint64_t buffer, viewOffset, viewLength, stride;
        if (!view.is_object()) return fail(vp, kRuleBufferView, "is not an object");
        if (!uintAt(view, "buffer", vp, kRuleBufferView, 0, buffer, true) ||
            !uintAt(view, "byteOffset", vp, kRuleBufferView, kMaxJsonInteger, viewOffset, false) ||
            !uintAt(view, "byteLength", vp, kRuleBufferView, kMaxJsonInteger, viewLength, true) ||
            !uintAt(view, "byteStride", vp, kRuleBufferView, 252, stride, false))
            return false;
        if (viewLength == 0) return fail(vp + ".byteLength", kRuleBufferView, "is 0");
        if (viewOffset + viewLength > bufferLength_)
            return fail(vp, kRuleBufferView,
                        "bytes [" + str(viewOffset) + ", " + str(viewOffset + viewLength) + ") exceed buffer 0's " +
                            str(bufferLength_) + " bytes");
        const uint64_t elemSize = uint64_t(csize) * actual;
        out.viewHasStride = member(view, "byteStride") != nullptr;
        if (!out.viewHasStride) stride = elemSize;
        if (stride < elemSize || stride % csize != 0)
            return fail(vp + ".byteStride", kRuleBufferView,
                        str(stride) + " does not fit accessor " + str(index) + "'s " + str(elemSize) + "-byte elements");
        out = View{index, bv, viewOffset + accOffset, count, stride, int(ct), actual, out.viewHasStride};
        if (accOffset > viewLength || out.byteSize() > viewLength - accOffset)
            return fail(ap, kRuleAccessor,
                        "byteOffset " + str(accOffset) + " + " + str(out.byteSize()) + " bytes exceed bufferView " +
                            str(bv) + "'s byteLength " + str(viewLength));
        if (out.offset % csize != 0)
            return fail(ap, kRuleAccessor, "data offset " + str(out.offset) + " is not a multiple of " + str(csize));
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
        return Packed{bin_ + v.offset, size_t(v.count) * size_t(v.components), v.componentType};
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
            loadValues(element, Packed{bin_ + v.offset + e * v.stride, size_t(v.components), v.componentType});
            out.insert(out.end(), element.begin(), element.end());
        }
    }

    // --- rule 8: the one primitive with the extension ----------------------------------
    bool findPrimitive() {
        const Json* used = arrayAt(doc_, "extensionsUsed");
        if (!used || std::find(used->begin(), used->end(), kExtensionName) == used->end())
            return fail("extensionsUsed", kRuleExtensionPlacement, std::string("does not list ") + kExtensionName);
        const Json* required = arrayAt(doc_, "extensionsRequired");
        if (required && std::find(required->begin(), required->end(), kExtensionName) != required->end())
            return fail("extensionsRequired", kRuleExtensionPlacement,
                        std::string("lists ") + kExtensionName + " (the fallback is always valid)");
        if (const Json* meshes = arrayAt(doc_, "meshes"))
            for (size_t m = 0; m < meshes->size(); ++m) {
                const Json* prims = arrayAt((*meshes)[m], "primitives");
                for (size_t p = 0; prims && p < prims->size(); ++p) {
                    const Json* exts = member((*prims)[p], "extensions");
                    const Json* ext = exts ? member(*exts, kExtensionName) : nullptr;
                    if (!ext) continue;
                    const std::string path = "meshes[" + str(m) + "].primitives[" + str(p) + "]";
                    if (prim_) return fail(path, kRuleExtensionPlacement, "a second primitive carries the extension");
                    prim_ = &(*prims)[p];
                    ext_ = ext;
                    primPath_ = path;
                    extPath_ = path + ".extensions." + kExtensionName;
                }
            }
        if (!prim_) return fail("meshes", kRuleExtensionPlacement, "no primitive carries the extension");
        return true;
    }

    // --- rules 12, 13: the extension object -----------------------------------------
    bool extension() {
        const Json& e = *ext_;
        if (!e.is_object()) return fail(extPath_, kRuleExtensionObject, "is not an object");
        const Json* version = member(e, "version");
        if (!version || !version->is_number_integer() || version->get<int64_t>() != kExtensionVersion) {
            fail(extPath_ + ".version", kRuleVersion,
                 (version ? version->dump() : std::string("missing")) + ", this reader knows version " +
                     str(kExtensionVersion));
            status_.code = Status::Unsupported;
            return false;
        }
        uint64_t maxDepth;
        if (!uintAt(e, "maxDepth", extPath_, kRuleExtensionObject, kMaxDepthLimit, maxDepth, true)) return false;
        const Json* b = member(e, "boundaryInterpolation");
        if (!b || !b->is_string() || !parseBoundaryName(b->get<std::string>(), asset_.boundary))
            return fail(extPath_ + ".boundaryInterpolation", kRuleExtensionObject,
                        "missing or not NONE, EDGE_AND_CORNER or EDGE_ONLY");
        const Json* c = member(e, "creaseMethod");
        if (!c || !c->is_string() || !parseCreaseMethodName(c->get<std::string>(), asset_.creaseMethod))
            return fail(extPath_ + ".creaseMethod", kRuleExtensionObject, "missing or not NORMAL or CHAIKIN");
        if (member(e, "controlVertex") && !accessorRef(e, "controlVertex", extPath_, kRuleExtensionObject, 0,
                                                       kPropControlVertex, typesOf(Elem::Index), 1))
            return false;
        const Json* levels = arrayAt(e, "levels");
        if (!levels || levels->size() != maxDepth + 1)
            return fail(extPath_ + ".levels", kRuleExtensionObject,
                        "missing or not an array of maxDepth + 1 = " + str(maxDepth + 1) + " level objects");
        asset_.levels.resize(levels->size());
        for (size_t l = 0; l < levels->size(); ++l) {
            const Json& lv = (*levels)[l];
            const std::string lp = extPath_ + ".levels[" + str(l) + "]";
            uint64_t first;
            if (!lv.is_object()) return fail(lp, kRuleExtensionObject, "is not an object");
            if (!uintAt(lv, "firstVertex", lp, kRuleExtensionObject, 0xFFFFFFFFull, first, true)) return false;
            asset_.levels[l].refinement.firstVertex = uint32_t(first);
            for (size_t p = 0; p < kLevelPropertyCount; ++p) {
                const LevelProperty& prop = kLevelProperties[p];
                if (member(lv, prop.name) && !accessorRef(lv, prop.name, lp, kRuleExtensionObject, l, int(p),
                                                          typesOf(prop.elem), prop.components))
                    return false;
            }
        }
        if (member(e, "editValues") &&
            !accessorRef(e, "editValues", extPath_, kRuleExtensionObject, 0, kPropEditValues, typesOf(Elem::Float), 3))
            return false;
        const Json* d = member(e, "displacement");
        return !d || displacement(*d, extPath_ + ".displacement");
    }

    // --- rules 36, 37: the displacement object (its tables: displacementTables) ------------
    bool displacement(const Json& d, const std::string& path) {
        if (!d.is_object()) return fail(path, kRuleDisplacementObject, "is not an object");
        DisplacementMap& map = asset_.displacement;
        uint64_t resolution;
        if (!uintAt(d, "resolution", path, kRuleDisplacementObject, kMaxJsonInteger, resolution, true)) return false;
        if (resolution == 0 || resolution > kMaxDisplacementResolution || (resolution & (resolution - 1)) != 0)
            return fail(path + ".resolution", kRuleDisplacementParams,
                        str(resolution) + " is not a power of two from 1 to " + str(kMaxDisplacementResolution));
        map.resolution = uint32_t(resolution);
        for (auto [key, out] : {std::pair<const char*, float*>{"scale", &map.scale}, {"bias", &map.bias}}) {
            const Json* v = member(d, key);
            if (!v || !v->is_number())
                return fail(path + "." + key, kRuleDisplacementObject, "missing or not a number");
            const double value = v->get<double>();
            if (!(std::fabs(value) <= double(std::numeric_limits<float>::max())))
                return fail(path + "." + key, kRuleDisplacementParams, v->dump() + " is not a finite float");
            *out = float(value);
        }
        static const int u16[] = {kU16, 0};
        const std::pair<const char*, int> accessors[] = {{"faceEdges", kPropFaceEdges}, {"values", kPropValues}};
        for (auto [key, prop] : accessors)
            if (!accessorRef(d, key, path, kRuleDisplacementObject, 0, prop,
                             prop == kPropValues ? u16 : typesOf(Elem::Index), prop == kPropValues ? 1 : 3))
                return false;
        return true;
    }

    // Decodes the displacement map's accessors (sizes: validateTables, rules 38, 39).
    bool displacementTables() {
        DisplacementMap& map = asset_.displacement;
        for (const Ref& r : refs_) {
            if (r.prop == kPropFaceEdges) values(r.view, map.faceEdges);
            if (r.prop != kPropValues) continue;
            const Packed p = packed(r.view);
            map.values.resize(p.count);
            for (size_t i = 0; i < p.count; ++i) map.values[i] = loadLE<uint16_t>(p.data + 2 * i);
        }
        return true;
    }

    // --- rule 40: editValues, alone on its bufferView, split into the levels -------------
    bool editTables() {
        const Ref* ref = nullptr;
        for (const Ref& r : refs_) ref = r.prop == kPropEditValues ? &r : ref;
        const Json* accessors = arrayAt(doc_, "accessors");
        for (size_t i = 0; ref && i < accessors->size(); ++i) {
            const Json* bv = member((*accessors)[i], "bufferView");
            if (i != ref->view.index && bv && *bv == ref->view.bufferView)
                return fail(ref->path, kRuleEditValues, "its bufferView " + str(ref->view.bufferView) +
                                                            " is also used by accessor " + str(i));
        }
        status_ = assignEditValues(asset_, ref ? packed(ref->view) : Packed{}, name_, extPath_ + ".editValues");
        return bool(status_);
    }

    // --- rule 14: the extension's accessors are distinct, packed and disjoint ------------
    bool disjoint() {
        std::vector<std::pair<uint64_t, size_t>> order;   // (data offset, ref)
        for (size_t i = 0; i < refs_.size(); ++i) {
            if (refs_[i].view.viewHasStride)
                return fail(refs_[i].path, kRuleAccessorsDisjoint,
                            "accessor " + str(refs_[i].view.index) + "'s bufferView has a byteStride");
            order.emplace_back(refs_[i].view.offset, i);
        }
        std::sort(order.begin(), order.end());
        for (size_t k = 1; k < order.size(); ++k) {
            const Ref& a = refs_[order[k - 1].second];
            const Ref& b = refs_[order[k].second];
            if (a.view.index == b.view.index)
                return fail(b.path, kRuleAccessorsDisjoint,
                            "accessor " + str(b.view.index) + " is also used by " + a.path);
            if (a.view.offset + a.view.byteSize() > b.view.offset)
                return fail(b.path, kRuleAccessorsDisjoint,
                            "accessor " + str(b.view.index) + "'s bytes overlap those of accessor " + str(a.view.index) +
                                " (" + a.path + ")");
        }
        return true;
    }

    // --- rules 9, 10, 11: the fallback primitive -> control mesh ------------------------
    bool attribute(const char* key, const std::string& attrsPath, int components, bool required, View& v) {
        const Json* attrs = member(*prim_, "attributes");
        uint64_t index;
        if (!attrs || !attrs->is_object())
            return fail(primPath_ + ".attributes", kRuleFallbackPrimitive, "missing or not an object");
        if (!member(*attrs, key)) return required ? fail(attrsPath, kRuleFallbackPrimitive, std::string("no ") + key) : true;
        static const int f32[] = {kF32, 0};
        return uintAt(*attrs, key, attrsPath, kRuleFallbackPrimitive, kMaxJsonInteger, index, true) &&
               resolve(index, attrsPath + "." + key, f32, components, v);
    }

    bool primitive() {
        const std::string ap = primPath_ + ".attributes";
        uint64_t mode, index;
        View pos, uv, idx;
        if (!uintAt(*prim_, "mode", primPath_, kRuleFallbackPrimitive, kMaxJsonInteger, mode, false, 4)) return false;
        if (mode != 4) return fail(primPath_ + ".mode", kRuleFallbackPrimitive, str(mode) + " is not TRIANGLES (4)");
        if (!attribute("POSITION", ap, 3, true, pos) || !attribute("TEXCOORD_0", ap, 2, false, uv)) return false;
        const uint64_t vcount = pos.count;
        if (uv.count != 0 && uv.count != vcount)
            return fail(ap + ".TEXCOORD_0", kRuleFallbackPrimitive,
                        str(uv.count) + " elements, POSITION has " + str(vcount));
        std::vector<float> positions, uvs;
        std::vector<uint32_t> indices;
        values(pos, positions);
        if (uv.count) values(uv, uvs);
        if (member(*prim_, "indices")) {
            static const int types[] = {kU8, kU16, kU32, 0};
            if (!uintAt(*prim_, "indices", primPath_, kRuleFallbackPrimitive, kMaxJsonInteger, index, true) ||
                !resolve(index, primPath_ + ".indices", types, 1, idx))
                return false;
            values(idx, indices);
            const size_t bad = firstNotBelow(indices, vcount);
            if (bad < indices.size())
                return fail(primPath_ + ".indices[" + str(bad) + "]", kRuleFallbackPrimitive,
                            "index " + str(indices[bad]) + " is not below the vertex count " + str(vcount));
        } else {
            indices.resize(size_t(vcount));
            for (size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t(i);
        }
        if (indices.size() % 3 != 0)
            return fail(primPath_, kRuleFallbackPrimitive, str(indices.size()) + " corners is not a multiple of 3");
        if (!uvs.empty()) {
            asset_.faceUVs.resize(2 * indices.size());
            for (size_t i = 0; i < indices.size(); ++i) {
                asset_.faceUVs[2 * i] = uvs[2 * size_t(indices[i])];
                asset_.faceUVs[2 * i + 1] = uvs[2 * size_t(indices[i]) + 1];
            }
        }
        if (refs_.empty() || refs_[0].prop != kPropControlVertex) {   // no controlVertex: the identity
            asset_.positions = std::move(positions);
            asset_.faces = std::move(indices);
            return true;
        }
        return controlMesh(positions, indices);
    }

    // Rules 10, 11: primitive vertex -> control vertex through controlVertex
    // (control_mesh.cpp), its length checked before it is decoded.
    bool controlMesh(const std::vector<float>& positions, const std::vector<uint32_t>& indices) {
        const Ref& r = refs_[0];
        const uint64_t vcount = positions.size() / 3;
        if (r.view.count != vcount)
            return fail(r.path, kRuleControlVertexCover, str(r.view.count) + " entries, POSITION has " + str(vcount));
        std::vector<uint32_t> cv;
        values(r.view, cv);
        Status st = rebuildControlMesh(positions, indices, cv, name_, r.path, primPath_ + ".attributes.POSITION", asset_);
        if (!st && status_) status_ = st;
        return bool(st);
    }

    // --- rule 15: decode the level tables --------------------------------------------
    // Vertex indices are stored relative to their level's first vertex: the reader
    // adds firstVertex mod 2^32 and leaves the range check to the validator. That
    // is exact: a stored u32 value r maps into [first, first + count) iff r < count,
    // since a wrapped sum r + first - 2^32 is below `first`.
    bool tables() {
        size_t k = (!refs_.empty() && refs_[0].prop == kPropControlVertex) ? 1 : 0;
        for (size_t l = 0; l < asset_.levels.size(); ++l) {
            Level& level = asset_.levels[l];
            Packed rows[kRowCount];
            for (size_t p = 0; p < kRowCount; ++p)
                if (k < refs_.size() && refs_[k].level == l && refs_[k].prop == int(p)) rows[p] = packed(refs_[k++].view);
            if (!groupCounts(l, rows)) return false;
            const uint32_t first = level.refinement.firstVertex;
            const uint32_t parentFirst = l == 0 ? 0 : asset_.levels[l - 1].refinement.firstVertex;
            for (size_t p = 0; p < kRowCount; ++p) {
                const LevelProperty& prop = kLevelProperties[p];
                if (prop.group == Group::None)
                    prop.decode(level, rows[p], prop.base == Base::Parent ? parentFirst : prop.base == Base::Own ? first : 0);
            }
            // The validator's patch limits (its numbering, should rule 22 hold).
            PatchLimits limits;
            limits.range = {first, l == 0 ? asset_.controlVertexCount()
                                          : uint32_t(rows[kVertexParent].count + rows[kEdgeVerts].count / 4)};
            limits.level = uint32_t(l);
            limits.faces = asset_.faceCount();
            limits.stencils = uint32_t(rows[kLimitVertex].count);
            limits.finest = l + 1 == asset_.levels.size();
            patchesChecked_ &= decodePatches(level, limits, rows);
        }
        return true;
    }

    // Rule 15: every row of a group holds the patch count (fixed by its first row)
    // times its perItem values, or is absent when absence means all zero.
    bool groupCounts(size_t l, const Packed* rows) {
        size_t count[3] = {};
        bool known[3] = {};
        for (size_t p = 0; p < kRowCount; ++p) {
            const LevelProperty& prop = kLevelProperties[p];
            const int g = int(prop.group);
            if (prop.group == Group::None) continue;
            const size_t values = rows[p].count;
            if (!known[g]) {
                known[g] = true;
                count[g] = values / prop.perItem;
                if (values % prop.perItem == 0) continue;
                return fail(levelPath(l, prop.name), kRulePatchArrays,
                            str(values) + " values is not a multiple of " + str(prop.perItem));
            }
            if (values != count[g] * prop.perItem && !(values == 0 && prop.zeroWhenAbsent))
                return fail(levelPath(l, prop.name), kRulePatchArrays,
                            str(values) + " values, expected " + str(count[g] * prop.perItem) + " (" +
                                str(prop.perItem) + " for each of " + str(count[g]) + " patches)");
        }
        return true;
    }

    std::string levelPath(size_t l, const char* prop) const {
        return extPath_ + ".levels[" + str(l) + "]." + prop;
    }
};

// Index of the first value of `v` that is >= `limit`, or v.size().
size_t firstNotBelow(const std::vector<uint32_t>& v, uint64_t limit) {
    uint32_t max = 0;
    for (uint32_t x : v) max = std::max(max, x);
    if (max < limit) return v.size();
    return size_t(std::find_if(v.begin(), v.end(), [&](uint32_t x) { return x >= limit; }) - v.begin());
}

} // namespace

Status readAssetGlb(const uint8_t* data, size_t size, const std::string& name, Asset& asset) {
    try {
        if (!data && size != 0) return Status::error(Status::Usage, name + ": no data");
        return Reader(data, size, name).run(asset);
    } catch (const std::bad_alloc&) {
        return Status::error(Status::BadInput, name + ": out of memory while reading");
    } catch (const std::exception& e) {
        return Status::error(Status::BadInput, name + ": malformed glTF: " + e.what());
    }
}

} // namespace lt
