// bench/detail.cpp -- per-property bytes of a written GLB and savings estimates
// (detail.h).
#include "detail.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace ltbench {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr int kUnsignedInt = 5125;

uint32_t readU32(const std::vector<uint8_t>& b, size_t at) {
    return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}

// The writer's width for an index array: u16 when every value is below 65536.
size_t width(uint32_t maxValue) { return maxValue < 65536 ? 2 : 4; }

uint32_t maxOf(const uint32_t* begin, const uint32_t* end) {
    uint32_t m = 0;
    for (const uint32_t* p = begin; p != end; ++p) m = std::max(m, *p);
    return m;
}
uint32_t maxOf(const std::vector<uint32_t>& v) { return maxOf(v.data(), v.data() + v.size()); }

size_t absoluteBytes(const std::vector<uint32_t>& v) { return v.size() * width(maxOf(v)); }

// Bytes of `v` (indices of vertices of a level starting at `first`) stored
// relative to `first`; as now if some index lies below `first`.
size_t relativeBytes(const std::vector<uint32_t>& v, uint32_t first) {
    if (v.empty()) return 0;
    if (*std::min_element(v.begin(), v.end()) < first) return absoluteBytes(v);
    return v.size() * width(maxOf(v) - first);
}

uint32_t levelFirst(const lt::Asset& a, size_t l) { return l == 0 ? 0 : a.levels[l].refinement.firstVertex; }

// True when stencil k's ring position weights (entries 1..) are all equal and
// non-zero: Loop's smooth interior limit mask, computable from the valence.
bool smoothStencil(const lt::LimitStencils& s, uint32_t k) {
    const uint32_t b = s.start[k], e = s.start[k + 1];
    if (e - b < 2 || s.position[b + 1] == 0.0f) return false;
    for (uint32_t i = b + 2; i < e; ++i)
        if (std::fabs(s.position[i] - s.position[b + 1]) > 1e-6f * std::fabs(s.position[b + 1])) return false;
    return true;
}

// True when stencil k's neighbours (entries 1..) are, as a set, refinement row
// `row` of `next` (the next level's vertex point of the same vertex).
bool sameRing(const lt::LimitStencils& s, uint32_t k, const lt::Refinement& next, uint32_t row) {
    std::vector<uint32_t> a(s.ring.begin() + s.start[k] + 1, s.ring.begin() + s.start[k + 1]);
    std::vector<uint32_t> b(next.vertexRing.begin() + next.vertexRingStart[row],
                            next.vertexRing.begin() + next.vertexRingStart[row + 1]);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    return a == b;
}

} // namespace

std::vector<PropertyBytes> glbPropertyBytes(const std::vector<uint8_t>& glb) {
    std::vector<PropertyBytes> out;
    if (glb.size() < 20 || readU32(glb, 0) != kGlbMagic || readU32(glb, 16) != kChunkJson) return out;
    const size_t jsonLength = readU32(glb, 12);
    if (20 + jsonLength > glb.size()) return out;
    using Json = nlohmann::ordered_json;
    const Json doc = Json::parse(glb.begin() + 20, glb.begin() + 20 + long(jsonLength), nullptr, false);
    if (doc.is_discarded()) return out;
    const Json* levels = nullptr;
    for (const Json& prim : doc.value("/meshes/0/primitives"_json_pointer, Json::array())) {
        auto ext = prim.find("extensions");
        if (ext == prim.end() || !ext->contains("EXT_mesh_loop_subdivision")) continue;
        levels = &(*ext)["EXT_mesh_loop_subdivision"]["levels"];
        break;
    }
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

Savings estimateSavings(const lt::Asset& a) {
    Savings s;
    size_t indicesButRings = 0, limitCombined = 0;  // parts of s.combined
    for (size_t l = 0; l < a.levels.size(); ++l) {
        const lt::Level& level = a.levels[l];
        const lt::Refinement& r = level.refinement;
        const uint32_t first = levelFirst(a, l);
        // Index widths: refinement points into level l-1, patches and limit into l.
        if (l > 0) {
            const uint32_t parentFirst = levelFirst(a, l - 1);
            for (const auto* v : {&r.vertexParent, &r.vertexRing, &r.edgeVerts})
                indicesButRings += absoluteBytes(*v) - relativeBytes(*v, parentFirst);
        }
        std::vector<uint32_t> points;
        points.reserve(level.regular.size() * 12);
        for (const lt::RegularPatch& p : level.regular) points.insert(points.end(), p.points, p.points + 12);
        indicesButRings += absoluteBytes(points) - relativeBytes(points, first);
        indicesButRings += absoluteBytes(level.limit.vertex) - relativeBytes(level.limit.vertex, first);
        s.relativeIndices += absoluteBytes(level.limit.ring) - relativeBytes(level.limit.ring, first);

        // Limit stencils: smooth weights and rings shared with the next level.
        const lt::LimitStencils& ls = level.limit;
        if (ls.count() == 0) continue;
        std::unordered_map<uint32_t, uint32_t> rowOf;  // parent global vertex -> next level's row
        const lt::Refinement* next = l + 1 < a.levels.size() ? &a.levels[l + 1].refinement : nullptr;
        if (next)
            for (uint32_t i = 0; i < next->vertexPointCount(); ++i) rowOf.emplace(next->vertexParent[i], i);
        const size_t ringWidth = ls.ring.empty() ? 0 : width(maxOf(ls.ring));
        const size_t relRingWidth = ls.ring.empty() ? 0 : width(maxOf(ls.ring) - first);
        size_t smoothEntries = 0, otherStencils = 0, sharedEntries = 0;
        for (uint32_t k = 0; k < ls.count(); ++k) {
            const size_t entries = ls.start[k + 1] - ls.start[k];
            if (smoothStencil(ls, k)) smoothEntries += entries;
            else ++otherStencils;
            auto row = rowOf.find(ls.vertex[k]);
            if (row != rowOf.end() && sameRing(ls, k, *next, row->second)) sharedEntries += entries;
        }
        // Non-smooth stencils then need a row in a (stencil, weightStart) table.
        const size_t weights = smoothEntries * 12, flags = otherStencils * 8;
        const size_t smooth = weights > flags ? weights - flags : 0;
        s.smoothLimitWeights += smooth;
        s.sharedLimitRings += sharedEntries * ringWidth;
        const size_t ringNow = ls.ring.size() * ringWidth;
        const size_t ringCombined = (ls.ring.size() - sharedEntries) * relRingWidth;
        limitCombined += smooth + (ringNow - ringCombined);
    }
    s.relativeIndices += indicesButRings;
    s.combined = indicesButRings + limitCombined;
    return s;
}

} // namespace ltbench
