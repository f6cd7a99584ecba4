// formats/src/glb_write.cpp -- lt::writeAssetGlb: Asset -> GLB with the control
// mesh as the primitive's fallback and the tables in EXT_mesh_loop_subdivision.
//
// Determinism: JSON keys are emitted in insertion order (ordered_json), accessors
// in one fixed order (primitive, controlVertex, then every level's rows of
// kLevelProperties, then the displacement map's faceEdges and values, then
// editValues), nothing depends on hashing, time or the environment. A surface's
// table accessors are collected until its surface object is complete, then
// stored, in that order, either as one compressed stream or as plain bufferViews.
#include "layout.h"
#include "parallel.h"
#include "stream.h"
#include "looptess/version.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cstring>
#include <unordered_map>

namespace lt {
namespace {

using namespace fmt;
using Json = nlohmann::ordered_json;

uint32_t bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

// `values` as `componentType` (u: integers, f: floats), little-endian, tightly packed.
std::vector<uint8_t> littleEndian(const Column& values, int componentType) {
    const size_t width = size_t(componentSize(componentType));
    const size_t n = componentType == kF32 ? values.f.size() : values.u.size();
    std::vector<uint8_t> out(n * width);
    uint8_t* dst = out.data();
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    if (width == 4) {  // the values' own bytes
        const void* src = componentType == kF32 ? static_cast<const void*>(values.f.data()) : values.u.data();
        if (n) std::memcpy(dst, src, 4 * n);
        return out;
    }
#endif
    if (width == 1)
        for (size_t i = 0; i < n; ++i) dst[i] = uint8_t(values.u[i]);
    else if (width == 2)
        for (size_t i = 0; i < n; ++i) {
            dst[2 * i] = uint8_t(values.u[i]);
            dst[2 * i + 1] = uint8_t(values.u[i] >> 8);
        }
    else
        for (size_t i = 0; i < n; ++i) {
            const uint32_t v = componentType == kF32 ? bits(values.f[i]) : values.u[i];
            for (size_t b = 0; b < 4; ++b) dst[4 * i + b] = uint8_t(v >> (8 * b));
        }
    return out;
}

// Appends accessors (one bufferView each, 4-byte aligned) to the BIN chunk.
class BinBuilder {
public:
    Json accessors = Json::array();
    Json bufferViews = Json::array();
    std::vector<uint8_t> bin;

    BinBuilder() = default;
    // Appends after a document's own accessors, bufferViews and buffer 0's bytes.
    BinBuilder(Json acc, Json views, std::vector<uint8_t> data)
        : accessors(std::move(acc)), bufferViews(std::move(views)), bin(std::move(data)) {}

    // Adds `values` (u: integers, f: floats) as one accessor on a bufferView of its
    // own; returns its index. Its bytes count as table kind `kind` in `tb`.
    int add(const Column& values, int componentType, int components, int target, TableBytes& tb,
            size_t TableSizes::*kind) {
        const std::vector<uint8_t> data = littleEndian(values, componentType);
        tb.*kind += data.size();
        tb.encoded.*kind += data.size();
        accessors.push_back(accessor(values.size(), componentType, components));
        accessors.back()["bufferView"] = appendView(data, target);
        return int(accessors.size() - 1);
    }

    // Adds `values` as a table accessor of the surface being written: its bytes wait
    // in `pending` for flushTables. Returns its index.
    int addTable(const Column& values, int componentType, int components, TableBytes& tb, size_t TableSizes::*kind) {
        return addTable(littleEndian(values, componentType), values.size(), componentType, components, tb, kind);
    }
    // As above, with the values already as littleEndian gives them (`count` of them).
    int addTable(std::vector<uint8_t> data, size_t count, int componentType, int components, TableBytes& tb,
                 size_t TableSizes::*kind) {
        Pending p{accessors.size(), kind, componentSize(componentType), std::move(data)};
        tb.*kind += p.data.size();
        accessors.push_back(accessor(count, componentType, components));
        pending.push_back(std::move(p));
        return int(accessors.size() - 1);
    }

    // Stores the pending table accessors: one compressed stream named by `surface`'s
    // `compression` object, or (Compression::None, or a stream that would break rule
    // 46's ratio) a plain bufferView each.
    void flushTables(Compression compression, size_t threads, Json& surface, TableBytes& tb) {
        if (pending.empty()) return;
        if (compression != Compression::None && compressTables(compression, threads, surface, tb)) return;
        for (Pending& p : pending) {
            tb.encoded.*p.kind += p.data.size();
            accessors[p.accessor]["bufferView"] = appendView(p.data, 0);
        }
        pending.clear();
    }

private:
    struct Pending {
        size_t accessor;
        size_t TableSizes::*kind;
        int size;                   // bytes per value
        std::vector<uint8_t> data;  // little-endian values
    };
    std::vector<Pending> pending;

    // The table kinds, the stream's groups (what TableBytes::encoded apportions the
    // stream to). The stream keeps accessor order: a level's tables side by side,
    // within Zstandard's window of each other.
    static constexpr size_t TableSizes::*kKinds[] = {
        &TableSizes::controlMesh, &TableSizes::refinement, &TableSizes::masks,        &TableSizes::patches,
        &TableSizes::irregular,   &TableSizes::limit,      &TableSizes::displacement, &TableSizes::edits};

    // `fast`: Zstandard level 4, a frame per 8 MiB of planes (readers decode the
    // frames of a large stream in parallel; 4 MiB frames cost fandisk 24% more
    // bytes, 8 MiB the torus 2%). Level 4 (double-fast matching) writes the torus's
    // stream about 1.7 times as fast as level 5 (greedy), for 3-8% more bytes;
    // with matches from 4 bytes instead of 5 and its table of 8-byte matches at
    // 2^16 entries instead of 2^18 it writes 1.4% fewer bytes over the files of
    // tests/data (fandisk 5.6%, none more than 0.3% larger) as fast (bench/README.md;
    // its table of short matches, 2^18, is what holds the bytes: at 2^15 it writes
    // 12-20% faster, but ycb_mustard's file grows 4.5%). `max`: level 19, a frame
    // per 64 MiB (smaller frames cost the torus a quarter more bytes there).
    static constexpr ZstdSettings kFast{4, 16, 18, 4}, kMax{19};
    bool compressTables(Compression compression, size_t threads, Json& surface, TableBytes& tb) {
        const bool max = compression == Compression::Max;
        std::vector<StreamPart> parts;
        Json list = Json::array();
        uint64_t decoded = 0;
        for (const Pending& p : pending) {
            const size_t g = size_t(std::find(std::begin(kKinds), std::end(kKinds), p.kind) - kKinds);
            parts.push_back(StreamPart{p.data.data(), p.data.size() / size_t(p.size), p.size, int(g)});
            list.push_back(p.accessor);
            decoded += segmentBytes(parts.back().values, uint64_t(p.size));
        }
        std::vector<uint8_t> encoded;
        std::vector<size_t> groupBytes;
        if (!encodeStream(parts, max ? kMax : kFast, max ? 8 * kFrameBytes : kFrameBytes, threads, encoded, groupBytes))
            throw std::bad_alloc();
        if (decoded > kMaxStreamRatio * encoded.size()) return false;
        for (size_t g = 0; g < groupBytes.size(); ++g) tb.encoded.*kKinds[g] += groupBytes[g];
        Json obj;
        obj["method"] = kStreamMethod;
        obj["bufferView"] = appendView(encoded, 0);
        obj["accessors"] = std::move(list);
        surface["compression"] = std::move(obj);
        pending.clear();
        return true;
    }

    static Json accessor(size_t values, int componentType, int components) {
        assert(values % size_t(components) == 0 && values > 0);
        Json acc;
        acc["componentType"] = componentType;
        acc["count"] = values / size_t(components);
        acc["type"] = accessorTypeName(components);
        return acc;
    }

    // A bufferView over `data`, appended at a multiple of 4; returns its index.
    size_t appendView(const std::vector<uint8_t>& data, int target) {
        while (bin.size() % 4 != 0) bin.push_back(0);
        Json view;
        view["buffer"] = 0;
        view["byteOffset"] = bin.size();
        view["byteLength"] = data.size();
        if (target) view["target"] = target;
        bin.insert(bin.end(), data.begin(), data.end());
        bufferViews.push_back(std::move(view));
        return bufferViews.size() - 1;
    }
};

uint32_t maxOf(const std::vector<uint32_t>& v) {
    uint32_t m = 0;
    for (uint32_t x : v) m = std::max(m, x);
    return m;
}

// Index arrays: u16 when every value is below `limit16`, else u32.
int indexComponentType(const std::vector<uint32_t>& v, uint32_t limit16 = 65536) {
    return maxOf(v) < limit16 ? kU16 : kU32;
}

int componentTypeOf(Elem e, const Column& c) {
    switch (e) {
    case Elem::Index: return indexComponentType(c.u);
    case Elem::Small: return maxOf(c.u) < 256 ? kU8 : kU16;
    case Elem::U8: return kU8;
    case Elem::Float: return kF32;
    }
    return 0;
}

size_t TableSizes::*counter(Kind k) {
    switch (k) {
    case Kind::Refinement: return &TableSizes::refinement;
    case Kind::Masks: return &TableSizes::masks;
    case Kind::Patches: return &TableSizes::patches;
    case Kind::Irregular: return &TableSizes::irregular;
    case Kind::Limit: return &TableSizes::limit;
    case Kind::Edits: return &TableSizes::edits;
    }
    return &TableSizes::refinement;
}

// The fallback primitive's vertices: unique (control vertex, corner attributes)
// tuples in first-use order over the face corners -- TEXCOORD_0, TEXCOORD_1 and
// COLOR_0, compared bitwise -- then control vertices no face uses (attributes 0, 0
// and colour 1, 1, 1, 1). Without corner attributes: exactly the control vertices.
struct Fallback {
    std::vector<uint32_t> controlVertex;   // per primitive vertex
    std::vector<float> uvs, uvs1, colors;  // 2, 2 and 4 per primitive vertex, or empty
    std::vector<uint32_t> indices;         // 3 per face
    bool identity = true;
};

Fallback buildFallback(const Asset& a) {
    Fallback fb;
    const uint32_t n = a.controlVertexCount();
    if (a.faceUVs.empty() && a.faceUV1s.empty() && a.faceColors.empty()) {
        fb.controlVertex.resize(n);
        for (uint32_t v = 0; v < n; ++v) fb.controlVertex[v] = v;
        fb.indices = a.faces;
        return fb;
    }
    // Each corner attribute: its floats per corner and where the primitive's go.
    struct Channel {
        const std::vector<float>& perCorner;
        std::vector<float>& perVertex;
        size_t width;
        float unused;
    };
    Channel channels[] = {
        {a.faceUVs, fb.uvs, 2, 0.0f}, {a.faceUV1s, fb.uvs1, 2, 0.0f}, {a.faceColors, fb.colors, 4, 1.0f}};
    using Key = std::array<uint32_t, 9>;  // control vertex, then the attributes' bits
    struct KeyHash {
        size_t operator()(const Key& k) const {
            uint64_t h = 0;
            for (uint32_t x : k) h = (h ^ x) * 0x9E3779B97F4A7C15ull + (h >> 29);
            return size_t(h);
        }
    };
    std::unordered_map<Key, uint32_t, KeyHash> ids;
    ids.reserve(a.faces.size());
    std::vector<uint8_t> used(n, 0);
    fb.indices.resize(a.faces.size());
    for (size_t c = 0; c < a.faces.size(); ++c) {
        const uint32_t v = a.faces[c];
        Key key{};
        key[0] = v;
        size_t at = 1;
        for (const Channel& ch : channels)
            if (!ch.perCorner.empty()) {
                std::memcpy(&key[at], &ch.perCorner[ch.width * c], 4 * ch.width);
                at += ch.width;
            }
        auto [it, inserted] = ids.emplace(key, uint32_t(fb.controlVertex.size()));
        if (inserted) {
            fb.controlVertex.push_back(v);
            for (Channel& ch : channels)
                if (!ch.perCorner.empty())
                    ch.perVertex.insert(ch.perVertex.end(), &ch.perCorner[ch.width * c],
                                        &ch.perCorner[ch.width * (c + 1)]);
            used[v] = 1;
        }
        fb.indices[c] = it->second;
    }
    for (uint32_t v = 0; v < n; ++v)
        if (!used[v]) {
            fb.controlVertex.push_back(v);
            for (Channel& ch : channels)
                if (!ch.perCorner.empty()) ch.perVertex.insert(ch.perVertex.end(), ch.width, ch.unused);
        }
    fb.identity = fb.controlVertex.size() == n;
    for (uint32_t i = 0; fb.identity && i < fb.controlVertex.size(); ++i) fb.identity = fb.controlVertex[i] == i;
    return fb;
}

// POSITION, TEXCOORD_0, TEXCOORD_1, COLOR_0 and indices of the primitive.
void writePrimitive(const Asset& a, const Fallback& fb, BinBuilder& bb, Json& prim, TableBytes& tb) {
    constexpr size_t TableSizes::*bytes = &TableSizes::controlMesh;
    Column pos;
    pos.f.resize(3 * fb.controlVertex.size());
    for (size_t i = 0; i < fb.controlVertex.size(); ++i)
        for (int k = 0; k < 3; ++k) pos.f[3 * i + k] = a.positions[3 * size_t(fb.controlVertex[i]) + k];
    Json attributes;
    attributes["POSITION"] = bb.add(pos, kF32, 3, kTargetArrayBuffer, tb, bytes);
    Json mn = Json::array(), mx = Json::array();
    for (int k = 0; k < 3; ++k) {
        float lo = pos.f[k], hi = pos.f[k];
        for (size_t i = 1; i < fb.controlVertex.size(); ++i) {
            lo = std::min(lo, pos.f[3 * i + k]);
            hi = std::max(hi, pos.f[3 * i + k]);
        }
        mn.push_back(double(lo));
        mx.push_back(double(hi));
    }
    bb.accessors.back()["min"] = mn;
    bb.accessors.back()["max"] = mx;
    const std::pair<const char*, const std::vector<float>*> extra[] = {
        {"TEXCOORD_0", &fb.uvs}, {"TEXCOORD_1", &fb.uvs1}, {"COLOR_0", &fb.colors}};
    for (const auto& [name, values] : extra) {
        if (values->empty()) continue;
        Column c;
        c.f = *values;
        attributes[name] = bb.add(c, kF32, values == &fb.colors ? 4 : 2, kTargetArrayBuffer, tb, bytes);
    }
    prim["attributes"] = attributes;
    Column idx;
    idx.u = fb.indices;
    // 65535 is the u16 primitive restart value, which glTF forbids in indices.
    prim["indices"] = bb.add(idx, indexComponentType(idx.u, 65535), 1, kTargetElementArrayBuffer, tb, bytes);
    prim["mode"] = 4;
}

// One level property's accessor, ready to add: its values' bytes (littleEndian),
// count and component type; count 0 when the property is omitted.
struct LevelTable {
    std::vector<uint8_t> data;
    size_t count = 0;
    int componentType = 0;
};

// Property p of `level`; vertex indices stored relative to the first vertex of the
// level they point into (`parentFirst`: level l-1, `first`: level l). The asset is
// valid, so no subtraction wraps.
LevelTable levelTable(const Level& level, size_t p, uint32_t parentFirst, uint32_t first) {
    const LevelProperty& prop = kLevelProperties[p];
    LevelTable t;
    Column c;
    prop.get(level, c);
    if (c.size() == 0 || (prop.zeroWhenAbsent && maxOf(c.u) == 0)) return t;
    const uint32_t base = prop.base == Base::Parent ? parentFirst : prop.base == Base::Own ? first : 0;
    if (base != 0)
        for (uint32_t& v : c.u) v -= base;
    t.componentType = componentTypeOf(prop.elem, c);
    t.count = c.size();
    t.data = littleEndian(c, t.componentType);
    return t;
}

// Level l's object over its tables (kLevelPropertyCount of them, levelTable's).
Json writeLevel(uint32_t first, LevelTable* tables, BinBuilder& bb, TableBytes& tb) {
    Json obj;
    obj["firstVertex"] = first;  // always present: no level object is ever empty
    for (size_t p = 0; p < kLevelPropertyCount; ++p) {
        const LevelProperty& prop = kLevelProperties[p];
        LevelTable& t = tables[p];
        if (t.count == 0) continue;
        obj[prop.name] =
            bb.addTable(std::move(t.data), t.count, t.componentType, prop.components, tb, counter(prop.kind));
    }
    return obj;
}

// The displacement object; its accessors follow every level's (faceEdges, then values).
Json writeDisplacement(const DisplacementMap& d, BinBuilder& bb, TableBytes& tb) {
    Json obj;
    obj["resolution"] = d.resolution;
    obj["scale"] = double(d.scale);  // shortest round-trip text: reads back to the same float
    obj["bias"] = double(d.bias);
    Column edges, values;
    edges.u = d.faceEdges;
    values.u.assign(d.values.begin(), d.values.end());
    obj["faceEdges"] = bb.addTable(edges, indexComponentType(edges.u), 3, tb, &TableSizes::displacement);
    obj["values"] = bb.addTable(values, kU16, 1, tb, &TableSizes::displacement);
    return obj;
}

// The mesh-level surface object: the tables of `asset` (spec "Extension object"),
// each level's property tables made on up to `threads` threads, then added in order.
Json surfaceObject(const Asset& asset, size_t threads, BinBuilder& bb, TableBytes& tb) {
    Json ext;
    ext["version"] = kFormatLayoutVersion;
    ext["maxDepth"] = asset.maxDepth();
    ext["boundaryInterpolation"] = boundaryName(asset.boundary);
    ext["creaseMethod"] = creaseMethodName(asset.creaseMethod);
    auto firstOf = [&](size_t l) { return asset.levels[l].refinement.firstVertex; };
    std::vector<LevelTable> tables(asset.levels.size() * kLevelPropertyCount);
    parallelFor(tables.size(), threads, 1, [&](size_t k, size_t) {
        const size_t l = k / kLevelPropertyCount;
        tables[k] = levelTable(asset.levels[l], k % kLevelPropertyCount, l == 0 ? 0 : firstOf(l - 1), firstOf(l));
    });
    Json levels = Json::array();
    for (size_t l = 0; l < asset.levels.size(); ++l)
        levels.push_back(writeLevel(firstOf(l), &tables[l * kLevelPropertyCount], bb, tb));
    ext["levels"] = std::move(levels);
    if (asset.displacement.present()) ext["displacement"] = writeDisplacement(asset.displacement, bb, tb);
    // The values of all levels' edits: one accessor, the last of the surface's, so a
    // loader can map or replace just them (on a bufferView of its own when plain).
    const Column values = editValues(asset);
    if (values.size() != 0) ext["editValues"] = bb.addTable(values, kF32, 3, tb, &TableSizes::edits);
    return ext;
}

bool isIdentity(const std::vector<uint32_t>& cv) {
    for (size_t i = 0; i < cv.size(); ++i)
        if (cv[i] != i) return false;
    return true;
}

// Puts a surface on mesh `mesh` (its tables) and the mesh's primitives `primitives`
// (its cage, each with its controlVertex map: empty or the identity is omitted),
// appending their accessors to `bb`. The caller has validated `asset`.
Status addSurface(Json& doc, uint32_t mesh, const std::vector<uint32_t>& primitives,
                  const std::vector<std::vector<uint32_t>>& controlVertex, const Asset& asset, BinBuilder& bb,
                  TableBytes& tb, Compression compression, size_t threads) {
    const std::string where = "writeSceneGlb: meshes[" + std::to_string(mesh) + "]";
    if (!doc.contains("meshes") || mesh >= doc["meshes"].size() || primitives.empty() ||
        controlVertex.size() != primitives.size())
        return Status::error(Status::Usage, where + ": no such mesh, or no cage primitives");
    Json& prims = doc["meshes"][mesh]["primitives"];
    for (size_t k = 0; k < primitives.size(); ++k) {
        if (primitives[k] >= prims.size())
            return Status::error(Status::Usage, where + ": no primitive " + std::to_string(primitives[k]));
        Json obj = Json::object();
        const std::vector<uint32_t>& cv = controlVertex[k];
        if (!cv.empty() && !isIdentity(cv)) {
            Column c;
            c.u = cv;
            obj["controlVertex"] = bb.addTable(c, indexComponentType(c.u), 1, tb, &TableSizes::controlMesh);
        }
        prims[primitives[k]]["extensions"][kExtensionName] = std::move(obj);
    }
    Json& surface = doc["meshes"][mesh]["extensions"][kExtensionName];
    surface = surfaceObject(asset, threads, bb, tb);
    bb.flushTables(compression, threads, surface, tb);
    Json& used = doc["extensionsUsed"];
    if (!used.is_array()) used = Json::array();
    if (std::find(used.begin(), used.end(), kExtensionName) == used.end()) used.push_back(kExtensionName);
    return Status::ok();
}

// The GLB container around `doc` (its accessors, bufferViews and one buffer from `bb`).
Status finishGlb(Json& doc, BinBuilder& bb, std::vector<uint8_t>& bytes) {
    while (bb.bin.size() % 4 != 0) bb.bin.push_back(0);
    doc["accessors"] = std::move(bb.accessors);
    doc["bufferViews"] = std::move(bb.bufferViews);
    doc["buffers"] = Json::array({Json{{"byteLength", bb.bin.size()}}});

    std::string text = doc.dump();
    while (text.size() % 4 != 0) text.push_back(' ');
    const uint64_t total = 12 + 8 + uint64_t(text.size()) + 8 + bb.bin.size();
    if (total > 0xFFFFFFFFull)
        return Status::error(Status::Unsupported,
                             "writeAssetGlb: the GLB would be " + std::to_string(total) + " bytes, more than 2^32 - 1");

    bytes.clear();
    bytes.reserve(size_t(total));
    appendU32(bytes, kGlbMagic);
    appendU32(bytes, kGlbVersion);
    appendU32(bytes, uint32_t(total));
    appendU32(bytes, uint32_t(text.size()));
    appendU32(bytes, kGlbChunkJson);
    bytes.insert(bytes.end(), text.begin(), text.end());
    appendU32(bytes, uint32_t(bb.bin.size()));
    appendU32(bytes, kGlbChunkBin);
    bytes.insert(bytes.end(), bb.bin.begin(), bb.bin.end());
    return Status::ok();
}

Status writeGlb(const Asset& asset, std::vector<uint8_t>& bytes, TableBytes* tableBytes, Compression compression,
                size_t threads) {
    Status st = validateAsset(asset, "writeAssetGlb");
    if (!st) return st;

    TableBytes tb;
    BinBuilder bb;
    const Fallback fb = buildFallback(asset);
    Json prim;
    writePrimitive(asset, fb, bb, prim, tb);

    Json doc;
    doc["asset"]["version"] = "2.0";
    doc["asset"]["generator"] = std::string("looptess loopbake ") + LOOPTESS_VERSION_STRING;
    doc["extensionsUsed"] = Json::array();
    doc["scene"] = 0;
    doc["scenes"] = Json::array({Json{{"nodes", Json::array({0})}}});
    doc["nodes"] = Json::array({Json{{"mesh", 0}}});
    doc["meshes"] = Json::array({Json{{"primitives", Json::array({prim})}}});
    const std::vector<std::vector<uint32_t>> cv = {fb.identity ? std::vector<uint32_t>{} : fb.controlVertex};
    if (st = addSurface(doc, 0, {0}, cv, asset, bb, tb, compression, threads); !st) return st;
    if (st = finishGlb(doc, bb, bytes); !st) return st;
    if (tableBytes) *tableBytes = tb;
    return Status::ok();
}

Status writeScene(std::string_view json, std::vector<uint8_t> bin, const std::vector<SceneSurface>& surfaces,
                  std::vector<uint8_t>& bytes, TableBytes* tableBytes, Compression compression, size_t threads) {
    Json doc = Json::parse(json);
    if (!doc.is_object()) return Status::error(Status::Usage, "writeSceneGlb: the document is not a JSON object");
    const Json* buffers = doc.contains("buffers") ? &doc["buffers"] : nullptr;
    if (buffers && (!buffers->is_array() || buffers->size() > 1 ||
                    (buffers->size() == 1 && (*buffers)[0].value("byteLength", uint64_t(0)) != bin.size())))
        return Status::error(Status::Usage, "writeSceneGlb: the document must have one buffer, the BIN given");
    TableBytes tb;
    BinBuilder bb(doc.value("accessors", Json::array()), doc.value("bufferViews", Json::array()), std::move(bin));
    for (const SceneSurface& sf : surfaces) {
        const std::string where = "writeSceneGlb: meshes[" + std::to_string(sf.mesh) + "]";
        if (Status st = validateAsset(sf.asset, where); !st) return st;
        if (Status st =
                addSurface(doc, sf.mesh, sf.primitives, sf.controlVertex, sf.asset, bb, tb, compression, threads);
            !st)
            return st;
    }
    if (Status st = finishGlb(doc, bb, bytes); !st) return st;
    if (tableBytes) *tableBytes = tb;
    return Status::ok();
}

}  // namespace

Status writeAssetGlb(const Asset& asset, std::vector<uint8_t>& bytes, TableBytes* tableBytes, Compression compression,
                     unsigned threads) {
    try {
        return writeGlb(asset, bytes, tableBytes, compression, threads);
    } catch (const std::bad_alloc&) {
        return Status::error(Status::WriteFailed, "writeAssetGlb: out of memory");
    } catch (const std::exception& e) {
        return Status::error(Status::Internal, std::string("writeAssetGlb: ") + e.what());
    }
}

Status writeSceneGlb(std::string_view json, std::vector<uint8_t> bin, const std::vector<SceneSurface>& surfaces,
                     std::vector<uint8_t>& bytes, TableBytes* tableBytes, Compression compression, unsigned threads) {
    try {
        return writeScene(json, std::move(bin), surfaces, bytes, tableBytes, compression, threads);
    } catch (const std::bad_alloc&) {
        return Status::error(Status::WriteFailed, "writeSceneGlb: out of memory");
    } catch (const std::exception& e) {
        return Status::error(Status::Internal, std::string("writeSceneGlb: ") + e.what());
    }
}

}  // namespace lt
