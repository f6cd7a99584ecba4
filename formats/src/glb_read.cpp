// formats/src/glb_read.cpp -- lt::readSceneGlb, lt::readAssetGlb: untrusted GLB
// bytes -> the surfaces of a scene.
//
// Order of work, so that nothing is allocated before the file justifies it:
//   1. GLB header and chunks (rules 1, 2), JSON nesting pre-scan and parse (3):
//      glb_container.cpp; the one buffer (4: glb_document.h);
//   2. the meshes carrying the extension and their cage primitives (8), every
//      surface object (12, 13) and its compression object (46: the accessors it
//      lists and the bytes they decode to, at most 256x its bufferView); every
//      accessor they name is resolved and range-checked (5, 6, 7: glb_document.h)
//      and the accessors and streams of all surfaces must be pairwise disjoint (14)
//      -- so all decoded tables together are at most 4 x 256 x the BIN chunk;
//   3. per surface: decode its stream (46), the cage primitives (9, 45), rebuild the control mesh
//      (10, 11: control_mesh.cpp) and the tables (15: level_decode.cpp, the levels'
//      arrays as tasks on a few threads) -- applying the validator's per-patch
//      checks on the way --, the displacement map (36) and edit values (40), then
//      validate the tables (16..44, levels on a few threads).
#include "glb_container.h"
#include "glb_document.h"
#include "reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>

namespace lt {
namespace {

using namespace fmt;

size_t firstNotBelow(const std::vector<uint32_t>& v, uint64_t limit);

// Ref::prop of the accessors that are not level rows.
constexpr int kPropControlVertex = -1, kPropFaceEdges = -2, kPropValues = -3, kPropEditValues = -4;

// An accessor named by the extension: controlVertex, a level row (prop >= 0, a
// Row), one of the displacement map's two or editValues.
struct Ref {
    size_t level = 0;  // controlVertex: the cage primitive
    int prop = -1;
    std::string path;
    View view;
};

class Reader : GlbDocument {
public:
    Reader(const uint8_t* data, size_t size, const std::string& name, size_t threads)
        : GlbDocument(name), data_(data), size_(size), threads_(threads) {}

    Status run(std::vector<SceneSurface>& out) {
        GlbContainer container;
        status_ = readGlbContainer(data_, size_, name_, container);
        if (!status_) return status_;
        doc_ = std::move(container.json);
        bin_ = container.bin;
        binLength_ = container.binLength;
        if (!buffer() || !findSurfaces()) return status_;
        for (size_t s = 0; s < surfaces_.size(); ++s) {
            if (!extension(s)) return status_;
            surfaces_[s].header = std::move(asset_);  // options, levels' firstVertex, displacement parameters
            asset_ = Asset{};
        }
        if (!disjoint() || !streamsCovered()) return status_;
        std::vector<SceneSurface> result(surfaces_.size());
        for (size_t s = 0; s < surfaces_.size(); ++s) {
            select(s);
            SceneSurface& r = result[s];
            if (!decodeStreams(s) || !cage(s, r) || !tables() || !displacementTables() || !editTables()) return status_;
            if (surfaces_[s].stream >= 0) streams_[size_t(surfaces_[s].stream)].data.reset();  // now in asset_
            const std::string name = surfaces_.size() == 1 ? name_ : name_ + ": meshes[" + str(surfaces_[s].mesh) + "]";
            if (Status st = validateTables(asset_, name, patchesChecked_, threads_); !st) return st;
            r.mesh = uint32_t(surfaces_[s].mesh);
            r.primitives = surfaces_[s].primitives;
            const Json* meshName = member((*arrayAt(doc_, "meshes"))[surfaces_[s].mesh], "name");
            if (meshName && meshName->is_string()) r.name = meshName->get<std::string>();
            r.asset = std::move(asset_);
        }
        out = std::move(result);
        return Status::ok();
    }

private:
    const uint8_t* data_;
    size_t size_;
    size_t threads_;         // for the level tables: tableThreads
    std::vector<Ref> refs_;  // every surface's accessors, surface after surface

    // A mesh carrying the extension and its cage primitives.
    struct Surface {
        size_t mesh = 0;
        const Json* ext = nullptr;
        std::string extPath;
        std::vector<uint32_t> primitives;
        size_t refBegin = 0, refEnd = 0;  // its refs_
        Asset header;                     // what extension() read
        int stream = -1;                  // its streams_ entry, if compressed
    };
    std::vector<Surface> surfaces_;
    // The surface being decoded (select).
    Asset asset_;
    const Json* ext_ = nullptr;
    std::string extPath_;
    size_t refBegin_ = 0, refEnd_ = 0;
    bool patchesChecked_ = true;  // every decoded patch passed regularOk / irregularOk
    uint64_t cageCorners_ = 0;    // rule 45: over every surface

    void select(size_t s) {
        asset_ = std::move(surfaces_[s].header);
        ext_ = surfaces_[s].ext;
        extPath_ = surfaces_[s].extPath;
        refBegin_ = surfaces_[s].refBegin;
        refEnd_ = surfaces_[s].refEnd;
        patchesChecked_ = true;
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
            !resolve(index, r.path, types, components, r.view, true))
            return false;
        refs_.push_back(std::move(r));
        return true;
    }

    // --- rule 8: the meshes carrying the extension and their cage primitives ----------
    bool findSurfaces() {
        const Json* used = arrayAt(doc_, "extensionsUsed");
        if (!used || std::find(used->begin(), used->end(), kExtensionName) == used->end())
            return fail("extensionsUsed", kRuleExtensionPlacement, std::string("does not list ") + kExtensionName);
        const Json* required = arrayAt(doc_, "extensionsRequired");
        if (required && std::find(required->begin(), required->end(), kExtensionName) != required->end())
            return fail("extensionsRequired", kRuleExtensionPlacement,
                        std::string("lists ") + kExtensionName + " (the fallback is always valid)");
        const Json* meshes = arrayAt(doc_, "meshes");
        for (size_t m = 0; meshes && m < meshes->size(); ++m) {
            const std::string mp = "meshes[" + str(m) + "]";
            const Json* exts = member((*meshes)[m], "extensions");
            Surface s;
            s.mesh = m;
            s.ext = exts ? member(*exts, kExtensionName) : nullptr;
            s.extPath = mp + ".extensions." + kExtensionName;
            const Json* prims = arrayAt((*meshes)[m], "primitives");
            for (size_t p = 0; prims && p < prims->size(); ++p) {
                const Json* pe = member((*prims)[p], "extensions");
                if (!pe || !member(*pe, kExtensionName)) continue;
                const std::string path = mp + ".primitives[" + str(p) + "].extensions." + kExtensionName;
                if (!s.ext && member(*member(*pe, kExtensionName), "version")) {
                    fail(path, kRuleVersion,
                         "tables on a primitive (version 1); this reader knows version " + str(kFormatLayoutVersion) +
                             ": bake the asset again");
                    status_.code = Status::Unsupported;
                    return false;
                }
                if (!s.ext)
                    return fail(path, kRuleExtensionPlacement, "the primitive's mesh carries no surface object");
                s.primitives.push_back(uint32_t(p));
            }
            if (s.ext && s.primitives.empty())
                return fail(s.extPath, kRuleExtensionPlacement, "no primitive of the mesh carries the extension");
            if (s.ext) surfaces_.push_back(std::move(s));
        }
        if (surfaces_.empty()) return fail("meshes", kRuleExtensionPlacement, "no mesh carries the extension");
        return true;
    }

    // --- rules 12, 13: the extension object -----------------------------------------
    bool extension(size_t s) {
        Surface& surface = surfaces_[s];
        ext_ = surface.ext;
        extPath_ = surface.extPath;
        surface.refBegin = refs_.size();
        bool ok = compression(surface) && cageRefs(surface) && extensionObject();
        surface.refEnd = refs_.size();
        return ok;
    }

    // Rule 10's accessors: each cage primitive's controlVertex (absent: the identity).
    bool cageRefs(const Surface& s) {
        const Json& prims = (*arrayAt(doc_, "meshes"))[s.mesh]["primitives"];
        for (size_t k = 0; k < s.primitives.size(); ++k) {
            const std::string path = primitivePath(s, k) + ".extensions." + kExtensionName;
            const Json& e = prims[s.primitives[k]]["extensions"][kExtensionName];
            if (!e.is_object()) return fail(path, kRuleExtensionObject, "is not an object");
            if (member(e, "controlVertex") && !accessorRef(e, "controlVertex", path, kRuleExtensionObject, k,
                                                           kPropControlVertex, typesOf(Elem::Index), 1))
                return false;
        }
        return true;
    }

    static std::string primitivePath(const Surface& s, size_t k) {
        return "meshes[" + str(s.mesh) + "].primitives[" + str(s.primitives[k]) + "]";
    }

    bool extensionObject() {
        const Json& e = *ext_;
        if (!e.is_object()) return fail(extPath_, kRuleExtensionObject, "is not an object");
        const Json* version = member(e, "version");
        if (!version || !version->is_number_integer() || version->get<int64_t>() != kFormatLayoutVersion) {
            fail(extPath_ + ".version", kRuleVersion,
                 (version ? version->dump() : std::string("missing")) + ", this reader knows version " +
                     str(kFormatLayoutVersion));
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
        for (size_t k = refBegin_; k < refEnd_; ++k) {
            const Ref& r = refs_[k];
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
        for (size_t k = refBegin_; k < refEnd_; ++k) ref = refs_[k].prop == kPropEditValues ? &refs_[k] : ref;
        const Json* accessors = arrayAt(doc_, "accessors");
        for (size_t i = 0; ref && i < accessors->size(); ++i) {
            const Json* bv = member((*accessors)[i], "bufferView");
            if (i != ref->view.index && bv && *bv == ref->view.bufferView)
                return fail(ref->path, kRuleEditValues,
                            "its bufferView " + str(ref->view.bufferView) + " is also used by accessor " + str(i));
        }
        status_ = assignEditValues(asset_, ref ? packed(ref->view) : Packed{}, name_, extPath_ + ".editValues");
        return bool(status_);
    }

    // --- rule 14: the extension's accessors are distinct, packed and disjoint ------------
    bool disjoint() {
        std::vector<std::tuple<uint32_t, uint64_t, size_t>> order;  // (stream, data offset, ref)
        for (size_t i = 0; i < refs_.size(); ++i) {
            if (refs_[i].view.viewHasStride)
                return fail(refs_[i].path, kRuleAccessorsDisjoint,
                            "accessor " + str(refs_[i].view.index) + "'s bufferView has a byteStride");
            order.emplace_back(refs_[i].view.stream, refs_[i].view.offset, i);
        }
        // The streams' own bytes take part, numbered after the refs (rule 46).
        std::vector<Ref> streamBytes(streams_.size());
        for (size_t k = 0; k < streams_.size(); ++k) {
            const Stream& st = streams_[k];
            streamBytes[k].path = st.path + ".bufferView";
            streamBytes[k].view = View{kNoView, st.bufferView, st.offset, st.length, 1, kU8, 1, false, 0};
            order.emplace_back(0, st.offset, refs_.size() + k);
        }
        auto ref = [&](size_t i) -> const Ref& { return i < refs_.size() ? refs_[i] : streamBytes[i - refs_.size()]; };
        std::sort(order.begin(), order.end());
        for (size_t k = 1; k < order.size(); ++k) {
            const Ref& a = ref(std::get<2>(order[k - 1]));
            const Ref& b = ref(std::get<2>(order[k]));
            if (a.view.index == b.view.index && a.view.index != kNoView)
                return fail(b.path, kRuleAccessorsDisjoint,
                            "accessor " + str(b.view.index) + " is also used by " + a.path);
            if (a.view.stream == b.view.stream && a.view.offset + a.view.byteSize() > b.view.offset)
                return fail(b.path, kRuleAccessorsDisjoint,
                            what(b) + "'s bytes overlap those of " + what(a) + " (" + a.path + ")");
        }
        return true;
    }

    static std::string what(const Ref& r) {
        return r.view.index == kNoView ? "bufferView " + str(r.view.bufferView) : "accessor " + str(r.view.index);
    }

    // --- rule 46: the compression object and its stream ---------------------------------
    // Reads surface `s`'s compression object (before its accessors are resolved):
    // the stream's bufferView and the segments of the accessors it lists.
    bool compression(Surface& s) {
        const Json* c = member(*s.ext, "compression");
        if (!c) return true;
        Stream st;
        st.path = s.extPath + ".compression";
        const Json* method = member(*c, "method");
        if (!c->is_object() || !method || !method->is_string() || method->get<std::string>() != kStreamMethod)
            return fail(st.path, kRuleCompression, std::string("not an object with method \"") + kStreamMethod + "\"");
        uint64_t stride;
        if (!uintAt(*c, "bufferView", st.path, kRuleCompression, arraySize("bufferViews"), st.bufferView, true))
            return false;
        if (st.bufferView == arraySize("bufferViews"))
            return fail(st.path + ".bufferView", kRuleCompression, "no such bufferView");
        if (!bufferView(st.bufferView, st.offset, st.length, stride)) return false;
        if (member((*arrayAt(doc_, "bufferViews"))[st.bufferView], "byteStride"))
            return fail(st.path + ".bufferView", kRuleCompression, "its bufferView has a byteStride");
        const Json* list = arrayAt(*c, "accessors");
        const Json* accessors = arrayAt(doc_, "accessors");
        if (!list || list->empty()) return fail(st.path + ".accessors", kRuleCompression, "missing or empty");
        for (size_t i = 0; i < list->size(); ++i) {
            const std::string lp = st.path + ".accessors[" + str(i) + "]";
            uint64_t index, ct, count;
            int components;
            if (!(*list)[i].is_number_unsigned() || !accessors ||
                (index = (*list)[i].get<uint64_t>()) >= accessors->size())
                return fail(lp, kRuleCompression, "is not an accessor index");
            const Json& acc = (*accessors)[index];
            const std::string ap = "accessors[" + str(index) + "]";
            if (!acc.is_object()) return fail(ap, kRuleAccessor, "is not an object");
            if (!streamed_.emplace(index, std::make_pair(uint32_t(streams_.size() + 1), st.decoded)).second)
                return fail(lp, kRuleCompression, "accessor " + str(index) + " is listed twice");
            for (const char* key : {"bufferView", "byteOffset", "sparse"})
                if (member(acc, key))
                    return fail(ap + "." + key, kRuleCompression, "an accessor in a compressed stream has none");
            if (!header(acc, ap, ct, count, components)) return false;
            const Segment seg{st.decoded, count * uint64_t(components), componentSize(int(ct))};
            st.decoded += segmentBytes(seg.values, uint64_t(seg.size));
            if (st.decoded > kMaxStreamRatio * st.length || st.decoded > 0xFFFFFFFFull)
                return fail(st.path, kRuleCompression,
                            "its accessors decode to more than " + str(kMaxStreamRatio) + " times bufferView " +
                                str(st.bufferView) + "'s " + str(st.length) + " bytes (or 2^32)");
            st.segments.push_back(seg);
        }
        s.stream = int(streams_.size());
        streams_.push_back(std::move(st));
        return true;
    }

    // Rule 46: the accessors a stream lists are exactly those of its own surface's
    // references that have no bufferView (rule 14 made each reference distinct, so
    // counting suffices).
    bool streamsCovered() {
        std::vector<size_t> used(streams_.size(), 0);
        for (size_t s = 0; s < surfaces_.size(); ++s)
            for (size_t k = surfaces_[s].refBegin; k < surfaces_[s].refEnd; ++k) {
                const Ref& r = refs_[k];
                if (!r.view.stream) continue;
                if (int(r.view.stream - 1) != surfaces_[s].stream)
                    return fail(r.path, kRuleCompression,
                                "accessor " + str(r.view.index) + " is in another surface's stream (" +
                                    streams_[r.view.stream - 1].path + ")");
                ++used[r.view.stream - 1];
            }
        for (size_t k = 0; k < streams_.size(); ++k)
            if (used[k] != streams_[k].segments.size())
                return fail(streams_[k].path + ".accessors", kRuleCompression,
                            "lists " + str(streams_[k].segments.size() - used[k]) +
                                " accessors that its surface does not reference");
        return true;
    }

    bool decodeStreams(size_t s) {
        if (surfaces_[s].stream < 0) return true;
        Stream& st = streams_[size_t(surfaces_[s].stream)];
        std::string error;
        if (!decodeStream(bin_ + st.offset, size_t(st.length), st.decoded, st.segments, st.data, error))
            return fail(st.path + ".bufferView", kRuleCompression, "bufferView " + str(st.bufferView) + ": " + error);
        return true;
    }

    // --- rules 9, 10, 11, 45: the cage primitives -> control mesh ------------------------
    bool attribute(const Json& prim, const char* key, const std::string& attrsPath, int components, bool required,
                   View& v) {
        const Json* attrs = member(prim, "attributes");
        uint64_t index;
        if (!attrs || !attrs->is_object()) return fail(attrsPath, kRuleFallbackPrimitive, "missing or not an object");
        if (!member(*attrs, key))
            return required ? fail(attrsPath, kRuleFallbackPrimitive, std::string("no ") + key) : true;
        static const int f32[] = {kF32, 0};
        return uintAt(*attrs, key, attrsPath, kRuleFallbackPrimitive, kMaxJsonInteger, index, true) &&
               resolve(index, attrsPath + "." + key, f32, components, v);
    }

    // Rule 9 for one cage primitive, decoded into `out` (its controlVertex: `cv`, or null).
    bool primitive(const Json& prim, const std::string& path, const Ref* cv, CagePrimitive& out) {
        const std::string ap = path + ".attributes";
        uint64_t mode, index;
        View pos, uv, idx;
        if (!uintAt(prim, "mode", path, kRuleFallbackPrimitive, kMaxJsonInteger, mode, false, 4)) return false;
        if (mode != 4) return fail(path + ".mode", kRuleFallbackPrimitive, str(mode) + " is not TRIANGLES (4)");
        if (!attribute(prim, "POSITION", ap, 3, true, pos) || !attribute(prim, "TEXCOORD_0", ap, 2, false, uv))
            return false;
        const uint64_t vcount = pos.count;
        if (uv.count != 0 && uv.count != vcount)
            return fail(ap + ".TEXCOORD_0", kRuleFallbackPrimitive,
                        str(uv.count) + " elements, POSITION has " + str(vcount));
        if (!extraAttribute(prim, "TEXCOORD_1", ap, {2}, 2, vcount, out.uvs1) ||
            !extraAttribute(prim, "COLOR_0", ap, {3, 4}, 4, vcount, out.colors))
            return false;
        if (cv && cv->view.count != vcount)
            return fail(cv->path, kRuleControlVertexCover,
                        str(cv->view.count) + " entries, POSITION has " + str(vcount));
        if (member(prim, "indices")) {
            static const int types[] = {kU8, kU16, kU32, 0};
            if (!uintAt(prim, "indices", path, kRuleFallbackPrimitive, kMaxJsonInteger, index, true) ||
                !resolve(index, path + ".indices", types, 1, idx))
                return false;
        }
        // Rule 45: primitives may share accessors, so bound what they decode together.
        cageCorners_ += (idx.count ? idx.count : vcount) + vcount;
        if (cageCorners_ > 8 * binLength_ + 64)
            return fail(path, kRuleCageSize,
                        "the cage primitives decode " + str(cageCorners_) +
                            " vertices and corners, more than 8 per byte of the buffer");
        values(pos, out.positions);
        if (uv.count) values(uv, out.uvs);
        if (cv) values(cv->view, out.cv);
        if (idx.count) {
            values(idx, out.indices);
            const size_t bad = firstNotBelow(out.indices, vcount);
            if (bad < out.indices.size())
                return fail(path + ".indices[" + str(bad) + "]", kRuleFallbackPrimitive,
                            "index " + str(out.indices[bad]) + " is not below the vertex count " + str(vcount));
        } else {
            out.indices.resize(size_t(vcount));
            for (size_t i = 0; i < out.indices.size(); ++i) out.indices[i] = uint32_t(i);
        }
        if (out.indices.size() % 3 != 0)
            return fail(path, kRuleFallbackPrimitive, str(out.indices.size()) + " corners is not a multiple of 3");
        out.path = path;
        out.cvPath = cv ? cv->path : path;
        return true;
    }

    // Every cage primitive of surface `s`, then rules 10, 11 (control_mesh.cpp).
    bool cage(size_t s, SceneSurface& out) {
        const Surface& surface = surfaces_[s];
        const Json& prims = (*arrayAt(doc_, "meshes"))[surface.mesh]["primitives"];
        std::vector<CagePrimitive> cage(surface.primitives.size());
        for (size_t k = 0; k < cage.size(); ++k) {
            const Ref* cv = nullptr;
            for (size_t r = refBegin_; r < refEnd_; ++r)
                if (refs_[r].prop == kPropControlVertex && refs_[r].level == k) cv = &refs_[r];
            if (!primitive(prims[surface.primitives[k]], primitivePath(surface, k), cv, cage[k])) return false;
        }
        Status st = rebuildControlMesh(cage, name_, asset_, out.primitiveFaces);
        if (!st && status_) status_ = st;
        out.controlVertex.resize(cage.size());
        for (size_t k = 0; k < cage.size(); ++k) out.controlVertex[k] = std::move(cage[k].cv);
        return bool(st);
    }

    // --- rule 15: decode the level tables (level_decode.cpp) -------------------------
    // Vertex indices are stored relative to their level's first vertex: the reader
    // adds firstVertex mod 2^32 and leaves the range check to the validator. That
    // is exact: a stored u32 value r maps into [first, first + count) iff r < count,
    // since a wrapped sum r + first - 2^32 is below `first`.
    bool tables() {
        std::vector<LevelRows> rows(asset_.levels.size());
        size_t k = refBegin_;
        while (k < refEnd_ && refs_[k].prop == kPropControlVertex) ++k;
        for (size_t l = 0; l < rows.size(); ++l)
            for (size_t p = 0; p < kRowCount; ++p)
                if (k < refEnd_ && refs_[k].level == l && refs_[k].prop == int(p)) rows[l][p] = packed(refs_[k++].view);
        status_ = decodeLevels(asset_, rows, threads_, name_, extPath_, patchesChecked_);
        return bool(status_);
    }
};

// Index of the first value of `v` that is >= `limit`, or v.size().
size_t firstNotBelow(const std::vector<uint32_t>& v, uint64_t limit) {
    uint32_t max = 0;
    for (uint32_t x : v) max = std::max(max, x);
    if (max < limit) return v.size();
    return size_t(std::find_if(v.begin(), v.end(), [&](uint32_t x) { return x >= limit; }) - v.begin());
}

}  // namespace

Status fmt::readSceneGlb(const uint8_t* data, size_t size, const std::string& name, std::vector<SceneSurface>& surfaces,
                         size_t threads) {
    try {
        if (!data && size != 0) return Status::error(Status::Usage, name + ": no data");
        return Reader(data, size, name, threads).run(surfaces);
    } catch (const std::bad_alloc&) {
        return Status::error(Status::BadInput, name + ": out of memory while reading");
    } catch (const std::exception& e) {
        return Status::error(Status::BadInput, name + ": malformed glTF: " + e.what());
    }
}

Status readSceneGlb(const uint8_t* data, size_t size, const std::string& name, std::vector<SceneSurface>& surfaces) {
    return fmt::readSceneGlb(data, size, name, surfaces, 0);
}

Status readAssetGlb(const uint8_t* data, size_t size, const std::string& name, Asset& asset) {
    std::vector<SceneSurface> surfaces;
    Status st = readSceneGlb(data, size, name, surfaces);
    if (st) asset = std::move(surfaces[0].asset);
    return st;
}

}  // namespace lt
