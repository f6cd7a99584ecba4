// bench/detail.cpp -- per-property bytes of a written GLB and savings estimates
// (detail.h).
#include "detail.h"

#include "looptess/glb.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace ltbench {
namespace {

constexpr int kUnsignedInt = 5125;

// `glb`'s chunks and its JSON chunk parsed as `Json`; false when it is not a GLB.
template <class Json>
bool readChunks(const std::vector<uint8_t>& glb, lt::GlbChunks& chunks, Json& doc) {
    if (!lt::readGlb(glb.data(), glb.size(), "glb", lt::GlbLayout::Strict, chunks)) return false;
    doc = Json::parse(chunks.json.begin(), chunks.json.end(), nullptr, false);
    return !doc.is_discarded();
}

// The writer's width for an index array: u16 when every value is below 65536.
size_t width(uint32_t maxValue) { return maxValue < 65536 ? 2 : 4; }

uint32_t maxOf(const uint32_t* begin, const uint32_t* end) {
    uint32_t m = 0;
    for (const uint32_t* p = begin; p != end; ++p) m = std::max(m, *p);
    return m;
}
uint32_t maxOf(const std::vector<uint32_t>& v) { return maxOf(v.data(), v.data() + v.size()); }

uint32_t levelFirst(const lt::Asset& a, size_t l) { return l == 0 ? 0 : a.levels[l].refinement.firstVertex; }

// Bytes of `v` (indices of the vertices of a level starting at `first`) as the
// writer stores them: relative to `first`.
size_t relativeBytes(const std::vector<uint32_t>& v, uint32_t first) {
    return v.empty() ? 0 : v.size() * width(maxOf(v) - first);
}

// True when stencil k's neighbours are, as a set, refinement row `row` of `next`
// (the next level's vertex point of the same vertex).
bool sameRing(const lt::LimitStencils& s, uint32_t k, const lt::Refinement& next, uint32_t row) {
    std::vector<uint32_t> a(s.ring.begin() + s.start[k], s.ring.begin() + s.start[k + 1]);
    std::vector<uint32_t> b(next.vertexRing.begin() + next.vertexRingStart[row],
                            next.vertexRing.begin() + next.vertexRingStart[row + 1]);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    return a == b;
}

// Bytes of a level's patch points (12 per patch) stored per chunk of kPatchChunk
// patches as a u32 base and u16 offsets (u32 points for a chunk whose span is
// 65536 or more).
constexpr size_t kPatchChunk = 64;
size_t chunkedPointBytes(const std::vector<uint32_t>& points) {
    size_t bytes = 0;
    for (size_t c = 0; c < points.size(); c += 12 * kPatchChunk) {
        const size_t end = std::min(points.size(), c + 12 * kPatchChunk);
        const uint32_t* b = points.data() + c;
        const uint32_t* e = points.data() + end;
        const uint32_t lo = *std::min_element(b, e), hi = maxOf(b, e);
        bytes += hi - lo < 65536 ? 4 + 2 * (end - c) : 4 * (end - c);
    }
    return bytes;
}

// The same after renumbering the level's vertices in order of first use.
size_t renumberedChunkedPointBytes(const std::vector<uint32_t>& points) {
    std::unordered_map<uint32_t, uint32_t> id;
    id.reserve(points.size() / 4);
    std::vector<uint32_t> renumbered(points.size());
    for (size_t i = 0; i < points.size(); ++i) renumbered[i] = id.emplace(points[i], uint32_t(id.size())).first->second;
    return chunkedPointBytes(renumbered);
}

}  // namespace

std::vector<PropertyBytes> glbPropertyBytes(const std::vector<uint8_t>& glb) {
    std::vector<PropertyBytes> out;
    using Json = nlohmann::ordered_json;
    lt::GlbChunks chunks;
    Json doc;
    if (!readChunks(glb, chunks, doc)) return out;
    // Version 2: the surface object (and its levels) sits on the mesh.
    const Json::json_pointer surface("/meshes/0/extensions/EXT_mesh_loop_subdivision/levels");
    const Json* levels = doc.contains(surface) ? &doc.at(surface) : nullptr;
    if (!levels || !levels->is_array()) return out;
    const Json& accessors = doc["accessors"];
    const Json& views = doc["bufferViews"];
    for (const Json& level : *levels) {
        for (auto it = level.begin(); it != level.end(); ++it) {
            if (it.key() == "firstVertex" || !it->is_number_unsigned()) continue;
            const Json& acc = accessors.at(it->get<size_t>());
            const size_t bytes = views.at(acc.at("bufferView").get<size_t>()).at("byteLength").get<size_t>();
            auto row = std::find_if(out.begin(), out.end(), [&](const PropertyBytes& p) { return p.name == it.key(); });
            if (row == out.end()) {
                out.push_back(PropertyBytes{it.key()});
                row = out.end() - 1;
            }
            row->bytes += bytes;
            if (acc.at("componentType").get<int>() == kUnsignedInt) row->wideBytes += bytes;
        }
    }
    return out;
}

uint64_t scanGlbInPlace(const std::vector<uint8_t>& glb) {
    using Json = nlohmann::json;
    lt::GlbChunks chunks;
    Json doc;
    if (!readChunks(glb, chunks, doc) || !chunks.bin || !doc.contains("accessors") || !doc.contains("bufferViews"))
        return 0;
    const Json& views = doc["bufferViews"];
    uint64_t result = 0;
    for (const Json& acc : doc["accessors"]) {
        const Json& view = views.at(acc.at("bufferView").get<size_t>());
        const size_t offset = view.value("byteOffset", size_t(0)), length = view.at("byteLength").get<size_t>();
        if (offset > chunks.binLength || length > chunks.binLength - offset) return 0;
        const uint8_t* p = chunks.bin + offset;
        const int type = acc.at("componentType").get<int>();
        const size_t size = type == 5121 ? 1 : type == 5123 ? 2 : 4;
        const size_t n = length / size;
        uint32_t acc32 = 0;
        if (type == 5126) {  // floats: all exponent bits set means Inf or NaN
            for (size_t i = 0; i < n; ++i) {
                uint32_t bits;
                std::memcpy(&bits, p + 4 * i, 4);
                acc32 |= uint32_t((bits & 0x7f800000u) == 0x7f800000u);
            }
        } else if (size == 4) {
            for (size_t i = 0; i < n; ++i) {
                uint32_t v;
                std::memcpy(&v, p + 4 * i, 4);
                acc32 = std::max(acc32, v);
            }
        } else if (size == 2) {
            for (size_t i = 0; i < n; ++i) {
                uint16_t v;
                std::memcpy(&v, p + 2 * i, 2);
                acc32 = std::max<uint32_t>(acc32, v);
            }
        } else {
            for (size_t i = 0; i < n; ++i) acc32 = std::max<uint32_t>(acc32, p[i]);
        }
        result = result * 31 + acc32;
    }
    return result;
}

Savings estimateSavings(const lt::Asset& a) {
    Savings s;
    for (size_t l = 0; l < a.levels.size(); ++l) {
        const lt::Level& level = a.levels[l];
        const uint32_t first = levelFirst(a, l);
        std::vector<uint32_t> points;
        points.reserve(level.regular.size() * 12);
        for (const lt::RegularPatch& p : level.regular) points.insert(points.end(), p.points, p.points + 12);
        const size_t pointsNow = relativeBytes(points, first);
        s.chunkedPatchPoints += pointsNow - std::min(pointsNow, chunkedPointBytes(points));
        s.renumberedChunkedPatchPoints += pointsNow - std::min(pointsNow, renumberedChunkedPointBytes(points));

        // Limit rings that repeat the next level's refinement ring of the same vertex.
        const lt::LimitStencils& ls = level.limit;
        if (ls.count() == 0 || l + 1 == a.levels.size()) continue;
        const lt::Refinement& next = a.levels[l + 1].refinement;
        std::unordered_map<uint32_t, uint32_t> rowOf;  // parent global vertex -> next level's row
        for (uint32_t i = 0; i < next.vertexPointCount(); ++i) rowOf.emplace(next.vertexParent[i], i);
        const size_t ringWidth = relativeBytes(ls.ring, first) / ls.ring.size();
        for (uint32_t k = 0; k < ls.count(); ++k) {
            auto row = rowOf.find(ls.vertex[k]);
            if (row != rowOf.end() && sameRing(ls, k, next, row->second))
                s.sharedLimitRings += (ls.start[k + 1] - ls.start[k]) * ringWidth;
        }
    }
    s.combined = s.chunkedPatchPoints + s.sharedLimitRings;
    return s;
}

}  // namespace ltbench
