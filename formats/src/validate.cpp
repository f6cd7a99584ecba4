// formats/src/validate.cpp -- lt::validateAsset: the table rules (16..35, 37..44) of
// formats/EXT_mesh_loop_subdivision/README.md, checked on an in-memory Asset (those
// of hierarchical edits, 40..44, in edits_io.cpp).
//
// Paths in messages use the file's property names (levels[2].edgeVerts[17]) so a
// message about a read file points at the accessor element that is wrong; vertex
// indices are quoted both relative to their level (as the file stores them) and
// global (as the Asset holds them).
//
// Speed: every rule is a linear pass; the hot ones are reductions that find
// whether anything is wrong before a second look finds what. Messages are built
// only on failure.
#include "layout.h"
#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

namespace lt {
namespace {

using namespace fmt;

std::string str(uint64_t v) { return std::to_string(v); }
std::string fstr(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    return buf;
}

std::string at(size_t l, const char* prop) { return "levels[" + str(l) + "]." + prop; }
std::string at(size_t l, const char* prop, size_t i) { return at(l, prop) + "[" + str(i) + "]"; }

// Index of the first of the n values at `v` outside `r`, or n.
size_t firstOutside(const uint32_t* v, size_t n, const Range& r) {
    uint32_t outside = 0;
    for (size_t i = 0; i < n; ++i) outside |= uint32_t(v[i] - r.begin >= r.count);
    if (!outside) return n;
    size_t i = 0;
    while (r.has(v[i])) ++i;
    return i;
}

// Index of the first value of `v` that is not finite, or v.size().
size_t firstNonFinite(const std::vector<float>& v) {
    uint32_t special = 0;  // exponent all ones: Inf or NaN
    for (float f : v) {
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        special |= uint32_t((bits & 0x7f800000u) == 0x7f800000u);
    }
    if (!special) return v.size();
    size_t i = 0;
    while (std::isfinite(v[i])) ++i;
    return i;
}

class Validator {
public:
    Validator(const Asset& a, const std::string& name, bool patchesChecked, size_t threads)
        : a_(a), name_(name), patchesChecked_(patchesChecked), threads_(threads) {}

    Status run() {
        if (controlMesh() && finite() && faces() && enums() && levelCount() && levelZero()) {
            bool ok = true;
            for (size_t l = 0; ok && l < a_.levels.size(); ++l) ok = sizes(l);
            ok = ok && numbering() && levels() && displacement();
        }
        return status_;
    }

private:
    const Asset& a_;
    const std::string& name_;
    const bool patchesChecked_;  // regularOk/irregularOk already passed on every patch
    const size_t threads_;       // for levels(): tableThreads
    Status status_;
    std::vector<Range> range_;  // per level, set by numbering()

    bool fail(const std::string& path, int rule, const std::string& what) {
        if (status_) status_ = ruleError(name_, path, rule, what);
        return false;
    }

    // Rule 16.
    bool controlMesh() {
        const uint64_t maxCount = std::numeric_limits<uint32_t>::max();
        if (a_.positions.empty() || a_.positions.size() % 3 != 0 || a_.positions.size() / 3 > maxCount)
            return fail("positions", kRuleControlMesh,
                        str(a_.positions.size()) + " floats is not a positive multiple of 3 below 3 * 2^32");
        if (a_.faces.empty() || a_.faces.size() % 3 != 0 || a_.faces.size() / 3 > maxCount)
            return fail("faces", kRuleControlMesh,
                        str(a_.faces.size()) + " indices is not a positive multiple of 3 below 3 * 2^32");
        const std::tuple<const std::vector<float>*, const char*, size_t> perCorner[] = {
            {&a_.faceUVs, "faceUVs", 2}, {&a_.faceUV1s, "faceUV1s", 2}, {&a_.faceColors, "faceColors", 4}};
        for (const auto& [values, name, width] : perCorner)
            if (!values->empty() && values->size() != width * a_.faces.size())
                return fail(name, kRuleControlMesh,
                            str(values->size()) + " floats, expected 0 or " + str(3 * width) + " per face (" +
                                str(width * a_.faces.size()) + ")");
        return true;
    }

    bool finiteArray(const std::vector<float>& v, const char* name, size_t level = SIZE_MAX) {
        const size_t i = firstNonFinite(v);
        if (i == v.size()) return true;
        return fail((level == SIZE_MAX ? std::string(name) : at(level, name)) + "[" + str(i) + "]", kRuleFinite,
                    "value is not finite");
    }

    // Rule 17, over every float array.
    bool finite() {
        if (!finiteArray(a_.positions, "positions") || !finiteArray(a_.faceUVs, "faceUVs") ||
            !finiteArray(a_.faceUV1s, "faceUV1s") || !finiteArray(a_.faceColors, "faceColors"))
            return false;
        for (size_t l = 0; l < a_.levels.size(); ++l) {
            const Level& lv = a_.levels[l];
            if (!finiteArray(lv.refinement.maskWeights, "maskWeights", l) ||
                !finiteArray(lv.refinement.creaseWeight, "creaseWeight", l) ||
                !finiteArray(lv.limit.position, "limitPosition", l) ||
                !finiteArray(lv.limit.tangentU, "limitTangentU", l) ||
                !finiteArray(lv.limit.tangentV, "limitTangentV", l))
                return false;
        }
        return true;
    }

    // Rule 18.
    bool faces() {
        const uint32_t n = a_.controlVertexCount();
        for (size_t f = 0; f < a_.faceCount(); ++f) {
            const uint32_t* c = &a_.faces[3 * f];
            for (int k = 0; k < 3; ++k)
                if (c[k] >= n)
                    return fail("faces[" + str(3 * f + k) + "]", kRuleFaces,
                                "index " + str(c[k]) + " is not below the control vertex count " + str(n));
            if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
                return fail(
                    "faces[" + str(3 * f) + "]", kRuleFaces,
                    "face " + str(f) + " repeats a vertex (" + str(c[0]) + ", " + str(c[1]) + ", " + str(c[2]) + ")");
        }
        return true;
    }

    // Rule 19.
    bool enums() {
        if (!boundaryName(a_.boundary))
            return fail("boundaryInterpolation", kRuleEnums, "unknown value " + str(uint32_t(a_.boundary)));
        if (!creaseMethodName(a_.creaseMethod))
            return fail("creaseMethod", kRuleEnums, "unknown value " + str(uint32_t(a_.creaseMethod)));
        return true;
    }

    // Rule 20.
    bool levelCount() {
        if (a_.levels.empty() || a_.levels.size() > kMaxDepthLimit + 1)
            return fail("levels", kRuleLevelCount,
                        str(a_.levels.size()) + " levels, expected 1 .. " + str(kMaxDepthLimit + 1) +
                            " (maxDepth 0 .. " + str(kMaxDepthLimit) + ")");
        return true;
    }

    // Rule 21.
    bool levelZero() {
        const Refinement& r = a_.levels[0].refinement;
        if (r.firstVertex != 0)
            return fail(at(0, "firstVertex"), kRuleLevelZero, "is " + str(r.firstVertex) + ", expected 0");
        if (!r.vertexParent.empty() || !r.vertexRingStart.empty() || !r.vertexRing.empty() || !r.maskedVertex.empty() ||
            !r.maskStart.empty() || !r.maskWeights.empty() || !r.edgeVerts.empty() || !r.creaseEdge.empty() ||
            !r.creaseWeight.empty())
            return fail("levels[0]", kRuleLevelZero, "level 0 has refinement tables");
        return true;
    }

    // Rule 23 for one CSR start array.
    bool csr(size_t l, const char* startName, const std::vector<uint32_t>& start, size_t count, const char* dataName,
             size_t dataSize) {
        if (start.empty() && count == 0 && dataSize == 0) return true;
        if (start.size() != count + 1)
            return fail(at(l, startName), kRuleCsr,
                        str(start.size()) + " entries, expected " + str(count + 1) + " (one per item plus one)");
        if (start[0] != 0) return fail(at(l, startName, 0), kRuleCsr, "is " + str(start[0]) + ", expected 0");
        bool decreases = false;
        for (size_t i = 1; i < start.size(); ++i) decreases |= start[i] < start[i - 1];
        for (size_t i = 1; decreases && i < start.size(); ++i)
            if (start[i] < start[i - 1])
                return fail(at(l, startName, i), kRuleCsr,
                            "is " + str(start[i]) + ", less than the previous entry " + str(start[i - 1]));
        if (start.back() != dataSize)
            return fail(
                at(l, startName, count), kRuleCsr,
                "last entry " + str(start.back()) + " differs from the size of " + dataName + ", " + str(dataSize));
        return true;
    }

    bool sameSize(size_t l, const char* name, size_t size, const char* refName, size_t refSize) {
        if (size == refSize) return true;
        return fail(at(l, name), kRuleParallelSizes,
                    str(size) + " entries, expected " + str(refSize) + " (as " + refName + ")");
    }

    // Rules 23 and 24 for level l.
    bool sizes(size_t l) {
        const Refinement& r = a_.levels[l].refinement;
        const LimitStencils& s = a_.levels[l].limit;
        if (r.edgeVerts.size() % 4 != 0)
            return fail(at(l, "edgeVerts"), kRuleParallelSizes,
                        str(r.edgeVerts.size()) + " entries is not a multiple of 4");
        return csr(l, "vertexRingStart", r.vertexRingStart, r.vertexParent.size(), "vertexRing", r.vertexRing.size()) &&
               csr(l, "maskStart", r.maskStart, r.maskedVertex.size(), "maskWeights", r.maskWeights.size()) &&
               csr(l, "limitStart", s.start, s.vertex.size(), "limitRing", s.ring.size()) &&
               csr(l, "limitMaskStart", s.maskStart, s.masked.size(), "limitPosition", s.position.size()) &&
               sameSize(l, "creaseWeight", r.creaseWeight.size(), "creaseEdge", r.creaseEdge.size()) &&
               sameSize(l, "limitTangentU", s.tangentU.size(), "limitPosition", s.position.size()) &&
               sameSize(l, "limitTangentV", s.tangentV.size(), "limitPosition", s.position.size());
    }

    // Rule 22; fills range_.
    bool numbering() {
        range_.assign(a_.levels.size(), Range{});
        range_[0] = {0, a_.controlVertexCount()};
        for (size_t l = 1; l < a_.levels.size(); ++l) {
            const Refinement& r = a_.levels[l].refinement;
            const uint64_t expected = uint64_t(range_[l - 1].begin) + range_[l - 1].count;
            if (r.firstVertex != expected)
                return fail(at(l, "firstVertex"), kRuleVertexNumbering,
                            "is " + str(r.firstVertex) + ", expected " + str(expected) + " (level " + str(l - 1) +
                                " ends there)");
            const uint64_t end = expected + r.vertexParent.size() + r.edgeVerts.size() / 4;
            if (end > std::numeric_limits<uint32_t>::max())
                return fail("levels[" + str(l) + "]", kRuleVertexNumbering,
                            "vertex count reaches " + str(end) + ", more than 2^32 - 1");
            range_[l] = {r.firstVertex, uint32_t(end - expected)};
        }
        return true;
    }

    // Rules 25..35 and 40..44, level by level. A level's rules read only its own
    // tables and range_ (every level's sizes are checked before), so the levels are
    // checked as independent tasks, each with a validator of its own; the first
    // level that fails, in level order, gives the status, as a serial walk would.
    bool levels() {
        const size_t n = a_.levels.size();
        uint64_t values = 0;
        for (const Level& lv : a_.levels) values += levelValues(lv);
        std::vector<Status> status(n);
        parallelTasks(n, tableThreads(values, threads_), [&](size_t l, size_t) {
            Validator v(a_, name_, patchesChecked_, 1);
            v.range_ = range_;
            v.level(l);
            status[l] = std::move(v.status_);
        });
        for (Status& st : status)
            if (!st) {
                status_ = std::move(st);
                return false;
            }
        return true;
    }

    bool level(size_t l) {
        return (l == 0 || refinement(l)) && (patchesChecked_ || (regular(l) && irregular(l))) && limit(l) && edits(l);
    }

    // Roughly the values of a level's tables: what its rules walk.
    static uint64_t levelValues(const Level& lv) {
        const Refinement& r = lv.refinement;
        return r.vertexParent.size() + r.vertexRing.size() + r.edgeVerts.size() + r.maskWeights.size() +
               12 * lv.regular.size() + 3 * lv.irregular.size() + lv.limit.ring.size() + lv.limit.position.size() +
               lv.edits.vertex.size();
    }

    // "relative index 12 (vertex 16) is not below level 1's vertex count 10"
    std::string outside(uint32_t v, size_t rangeLevel) const {
        const Range& r = range_[rangeLevel];
        return "relative index " + str(uint32_t(v - r.begin)) + " (vertex " + str(v) + ") is not below level " +
               str(rangeLevel) + "'s vertex count " + str(r.count);
    }

    bool indicesIn(size_t l, const char* name, const std::vector<uint32_t>& v, size_t rangeLevel, int rule) {
        const size_t i = firstOutside(v.data(), v.size(), range_[rangeLevel]);
        return i == v.size() || fail(at(l, name, i), rule, outside(v[i], rangeLevel));
    }

    // Rules 25..29 for level l >= 1.
    bool refinement(size_t l) {
        const Refinement& r = a_.levels[l].refinement;
        const Range& parent = range_[l - 1];
        if (!indicesIn(l, "vertexParent", r.vertexParent, l - 1, kRuleRefinementIndex) ||
            !indicesIn(l, "vertexRing", r.vertexRing, l - 1, kRuleRefinementIndex) ||
            !indicesIn(l, "edgeVerts", r.edgeVerts, l - 1, kRuleRefinementIndex))
            return false;

        const size_t vpCount = r.vertexParent.size();
        auto ringSize = [&](size_t v) -> size_t {
            return r.vertexRingStart.empty() ? 0 : r.vertexRingStart[v + 1] - r.vertexRingStart[v];
        };
        // Rule 27: explicit masks.
        std::vector<uint8_t> masked(vpCount, 0);
        for (size_t k = 0; k < r.maskedVertex.size(); ++k) {
            const uint32_t v = r.maskedVertex[k];
            if (v >= vpCount)
                return fail(at(l, "maskedVertex", k), kRuleMasks,
                            "local vertex point " + str(v) + " is not below the vertex point count " + str(vpCount));
            if (masked[v])
                return fail(at(l, "maskedVertex", k), kRuleMasks, "vertex point " + str(v) + " is masked twice");
            masked[v] = 1;
            const size_t weights = r.maskStart[k + 1] - r.maskStart[k];
            if (weights != ringSize(v))
                return fail(
                    at(l, "maskStart", k), kRuleMasks,
                    "mask has " + str(weights) + " weights, expected one per ring entry (" + str(ringSize(v)) + ")");
        }
        // Rule 26: vertex points.
        std::vector<uint8_t> parentSeen(parent.count, 0);
        for (size_t i = 0; i < vpCount; ++i) {
            uint8_t& seen = parentSeen[size_t(r.vertexParent[i] - parent.begin)];
            if (seen)
                return fail(at(l, "vertexParent", i), kRuleVertexPoints,
                            "parent vertex " + str(r.vertexParent[i]) + " has a second vertex point");
            seen = 1;
            if (!masked[i] && ringSize(i) == 0)
                return fail(at(l, "vertexRingStart", i), kRuleVertexPoints,
                            "smooth (unmasked) vertex point " + str(i) + " has an empty ring");
        }
        // Rule 28: edge points.
        for (size_t e = 0; e < r.edgePointCount(); ++e)
            if (r.edgeVerts[4 * e] == r.edgeVerts[4 * e + 1])
                return fail(at(l, "edgeVerts", 4 * e + 1), kRuleEdgePoints,
                            "edge point " + str(e) + " has equal endpoints " + str(r.edgeVerts[4 * e]));
        // Rule 29: creases.
        std::vector<uint8_t> creased(r.edgePointCount(), 0);
        for (size_t k = 0; k < r.creaseEdge.size(); ++k) {
            const uint32_t e = r.creaseEdge[k];
            if (e >= r.edgePointCount())
                return fail(
                    at(l, "creaseEdge", k), kRuleCreases,
                    "local edge point " + str(e) + " is not below the edge point count " + str(r.edgePointCount()));
            if (creased[e])
                return fail(at(l, "creaseEdge", k), kRuleCreases, "edge point " + str(e) + " is listed twice");
            creased[e] = 1;
            const float w = r.creaseWeight[k];
            if (!(w > 0.0f && w <= 1.0f))
                return fail(at(l, "creaseWeight", k), kRuleCreases, "weight " + fstr(w) + " is not in (0, 1]");
        }
        return true;
    }

    PatchLimits patchLimits(size_t l) const {
        PatchLimits k;
        k.range = range_[l];
        k.level = uint32_t(l);
        k.faces = a_.faceCount();
        k.stencils = a_.levels[l].limit.count();
        k.finest = l + 1 == a_.levels.size();
        return k;
    }

    // Rules 30..32 for level l's regular patches.
    bool regular(size_t l) {
        const auto& patches = a_.levels[l].regular;
        const PatchLimits k = patchLimits(l);
        for (size_t i = 0; i < patches.size(); ++i)
            if (!regularOk(patches[i], k)) return explainRegular(l, i);
        return true;
    }

    // Rules 32, 33 for level l's irregular faces.
    bool irregular(size_t l) {
        const auto& faces = a_.levels[l].irregular;
        const PatchLimits k = patchLimits(l);
        for (size_t i = 0; i < faces.size(); ++i)
            if (!irregularOk(faces[i], k)) return explainIrregular(l, i);
        return true;
    }

    // Why regularOk rejects regular patch i of level l.
    bool explainRegular(size_t l, size_t i) {
        const RegularPatch& p = a_.levels[l].regular[i];
        const size_t k = firstOutside(p.points, 12, range_[l]);
        if (k < 12)
            return fail(at(l, "regularPoints", 12 * i + k), kRulePatchPoints,
                        "patch " + str(i) + " point " + str(k) + ": " + outside(p.points[k], l));
        if (p.boundaryMask >= 64)
            return fail(at(l, "regularBoundaryMask", i), kRulePatchMasks,
                        "boundary mask " + str(p.boundaryMask) + " is not below 64");
        for (int c = 0; c < 3; ++c)  // corner c lies on edges c and (c + 2) % 3
            if ((p.boundaryMask >> (3 + c) & 1) && (p.boundaryMask >> c & 1 || p.boundaryMask >> (c + 2) % 3 & 1))
                return fail(at(l, "regularBoundaryMask", i), kRulePatchMasks,
                            "boundary mask " + str(p.boundaryMask) + " marks corner " + str(c) +
                                " although a boundary edge of the patch already ends there");
        if (p.splitMask >= 8)
            return fail(at(l, "regularSplitMask", i), kRulePatchMasks,
                        "split mask " + str(p.splitMask) + " is not below 8");
        if (l + 1 == a_.levels.size() && p.splitMask != 0)
            return fail(at(l, "regularSplitMask", i), kRulePatchMasks,
                        "split mask " + str(p.splitMask) + " on the finest level (no finer neighbours exist)");
        return explainParam(l, "regular", i, p.param);
    }

    // Why irregularOk rejects irregular face i of level l.
    bool explainIrregular(size_t l, size_t i) {
        const IrregularFace& f = a_.levels[l].irregular[i];
        const uint32_t stencils = a_.levels[l].limit.count();
        for (int k = 0; k < 3; ++k)
            if (f.corners[k] >= stencils)
                return fail(at(l, "irregularCorners", 3 * i + k), kRuleIrregularCorners,
                            "limit stencil " + str(f.corners[k]) + " is not below level " + str(l) +
                                "'s stencil count " + str(stencils));
        return explainParam(l, "irregular", i, f.param);
    }

    // Rule 32, for a patch that failed paramOk. `group` is "regular" or "irregular".
    bool explainParam(size_t l, const char* group, size_t i, const PatchParam& p) {
        const std::string base = group;
        if (p.level != l)  // only in-memory Assets: the reader sets the level
            return fail(at(l, (base + "Origin").c_str(), i), kRulePatchParam,
                        "patch level " + str(p.level) + " differs from the level index " + str(l));
        if (p.baseFace >= a_.faceCount())
            return fail(at(l, (base + "BaseFace").c_str(), i), kRulePatchParam,
                        "base face " + str(p.baseFace) + " is not below the face count " + str(a_.faceCount()));
        const uint64_t n = uint64_t(1) << l, ui = p.ui, vi = p.vi;
        if (p.rotated ? (ui >= 1 && vi >= 1 && ui + vi <= n) : (ui + vi < n)) {
            status_ = Status::error(Status::Internal, name_ + ": " + at(l, group) + "[" + str(i) +
                                                          "]: the fast and the detailed patch checks disagree");
            return false;
        }
        uint32_t stored[2];
        encodeOrigin(p, stored);
        return fail(at(l, (base + "Origin").c_str(), i), kRulePatchParam,
                    std::string(p.rotated ? "rotated" : "upright") + " origin (" + str(ui) + ", " + str(vi) +
                        "), stored as (" + str(stored[0]) + ", " + str(stored[1]) +
                        "), leaves the base triangle at level " + str(l) + " (a stored origin needs u, v < 2^level)");
    }

    // Rule 34 for level l's limit stencils.
    bool limit(size_t l) {
        const LimitStencils& s = a_.levels[l].limit;
        if (!indicesIn(l, "limitVertex", s.vertex, l, kRuleLimitStencils) ||
            !indicesIn(l, "limitRing", s.ring, l, kRuleLimitStencils))
            return false;
        for (size_t i = 0; i < s.vertex.size(); ++i) {
            const uint32_t b = s.start[i], e = s.start[i + 1];
            if (b == e) return fail(at(l, "limitStart", i + 1), kRuleLimitStencils, "stencil " + str(i) + " is empty");
            uint32_t smallest = s.ring[b];
            for (uint32_t k = b + 1; k < e; ++k) smallest = std::min(smallest, s.ring[k]);
            if (smallest == s.ring[b]) continue;
            const uint32_t k = uint32_t(std::find(s.ring.begin() + b, s.ring.begin() + e, smallest) - s.ring.begin());
            return fail(at(l, "limitRing", k), kRuleLimitStencils,
                        "stencil " + str(i) + ": neighbour " + str(smallest) + " is smaller than the first neighbour " +
                            str(s.ring[b]));
        }
        return limitMasks(l);
    }

    // Rule 35 for level l's limit stencils.
    bool limitMasks(size_t l) {
        const LimitStencils& s = a_.levels[l].limit;
        const uint32_t count = s.count();
        auto ringSize = [&](uint32_t i) { return s.start[i + 1] - s.start[i]; };
        size_t k = 0;  // the next entry of `masked`
        for (uint32_t i = 0; i < count; ++i) {
            if (k < s.masked.size() && s.masked[k] == i) {
                const uint32_t weights = s.maskStart[k + 1] - s.maskStart[k];
                if (weights != ringSize(i))
                    return fail(at(l, "limitMaskStart", k), kRuleLimitMasks,
                                "stencil " + str(i) + " has " + str(weights) +
                                    " weights, expected one per ring entry (" + str(ringSize(i)) + ")");
                ++k;
            } else if (ringSize(i) < 2) {
                return fail(
                    at(l, "limitStart", i + 1), kRuleLimitMasks,
                    "smooth (unmasked) stencil " + str(i) + " has " + str(ringSize(i)) + " ring entries, fewer than 2");
            }
        }
        if (k == s.masked.size()) return true;  // every entry matched a stencil, in increasing order
        return fail(at(l, "limitMasked", k), kRuleLimitMasks,
                    "stencil " + str(s.masked[k]) +
                        (s.masked[k] >= count ? " is not below the stencil count " + str(count)
                                              : " does not follow the previous entry " + str(s.masked[k - 1])));
    }

    // Rules 40..44 for level l's hierarchical edits.
    bool edits(size_t l) {
        status_ = validateEdits(a_, l, range_[l], name_);
        return bool(status_);
    }

    // Rules 37..39: the optional displacement map.
    bool displacement() {
        const DisplacementMap& d = a_.displacement;
        const uint32_t R = d.resolution;
        if (R == 0) {
            if (d.faceEdges.empty() && d.values.empty()) return true;
            return fail("displacement", kRuleDisplacementParams, "resolution 0 (no map) but face edges or samples");
        }
        if (R > kMaxDisplacementResolution || (R & (R - 1)) != 0)
            return fail("displacement.resolution", kRuleDisplacementParams,
                        str(R) + " is not a power of two from 1 to " + str(kMaxDisplacementResolution));
        if (!std::isfinite(d.scale)) return fail("displacement.scale", kRuleDisplacementParams, "is not finite");
        if (!std::isfinite(d.bias)) return fail("displacement.bias", kRuleDisplacementParams, "is not finite");
        uint64_t edges = 0;
        if (!faceEdges(edges)) return false;
        const uint64_t expected = displacementSampleCount(R, a_.controlVertexCount(), a_.faceCount(), edges);
        if (d.values.size() != expected)
            return fail("displacement.values", kRuleDisplacementSamples,
                        str(d.values.size()) + " samples, expected " + str(expected) + " (" +
                            str(a_.controlVertexCount()) + " vertices + " + str(a_.faceCount()) + " faces * " +
                            str((R - 1) * (R - 2) / 2) + " + " + str(edges) + " edges * " + str(R - 1) +
                            " at resolution " + str(R) + ")");
        return true;
    }

    // Rule 38: faceEdges numbers the control mesh's edges 0 .. E-1, one number per
    // unordered vertex pair, every number used. Sets `edgeCount` = E.
    bool faceEdges(uint64_t& edgeCount) {
        const std::vector<uint32_t>& fe = a_.displacement.faceEdges;
        const size_t corners = a_.faces.size();
        if (fe.size() != corners)
            return fail("displacement.faceEdges", kRuleFaceEdges,
                        str(fe.size()) + " entries, expected 3 per face (" + str(corners) + ")");
        const size_t big = std::max_element(fe.begin(), fe.end()) - fe.begin();
        edgeCount = uint64_t(fe[big]) + 1;
        if (edgeCount > corners)  // E distinct edges, each used: E <= 3F
            return fail("displacement.faceEdges[" + str(big) + "]", kRuleFaceEdges,
                        "edge " + str(fe[big]) + " is not below 3 * face count " + str(corners) +
                            " (edges are numbered 0 .. E-1, each used)");
        // Per edge: its unordered vertex pair (lo << 32 | hi), from its first use.
        std::vector<uint64_t> pairOf(static_cast<size_t>(edgeCount), UINT64_MAX);
        for (size_t k = 0; k < corners; ++k) {
            const uint32_t a = a_.faces[k], b = a_.faces[k - k % 3 + (k + 1) % 3];
            const uint64_t key = uint64_t(std::min(a, b)) << 32 | std::max(a, b);
            uint64_t& p = pairOf[fe[k]];
            if (p == UINT64_MAX)
                p = key;
            else if (p != key)
                return fail("displacement.faceEdges[" + str(k) + "]", kRuleFaceEdges,
                            "face " + str(k / 3) + " edge " + str(k % 3) + " (vertices " + str(a) + ", " + str(b) +
                                ") is numbered " + str(fe[k]) + ", which an earlier face uses for vertices " +
                                str(p >> 32) + ", " + str(p & 0xffffffffu));
        }
        std::vector<std::pair<uint64_t, uint32_t>> sorted(static_cast<size_t>(edgeCount));
        for (uint32_t e = 0; e < edgeCount; ++e) {
            if (pairOf[e] == UINT64_MAX)
                return fail("displacement.faceEdges", kRuleFaceEdges,
                            "no face uses edge " + str(e) + " of " + str(edgeCount));
            sorted[e] = {pairOf[e], e};
        }
        std::sort(sorted.begin(), sorted.end());
        for (size_t k = 1; k < sorted.size(); ++k)
            if (sorted[k].first == sorted[k - 1].first)
                return fail("displacement.faceEdges", kRuleFaceEdges,
                            "edges " + str(sorted[k - 1].second) + " and " + str(sorted[k].second) +
                                " both join vertices " + str(sorted[k].first >> 32) + ", " +
                                str(sorted[k].first & 0xffffffffu));
        return true;
    }
};

}  // namespace

Status fmt::validateTables(const Asset& asset, const std::string& name, bool patchesChecked, size_t threads) {
    try {
        return Validator(asset, name, patchesChecked, threads).run();
    } catch (const std::exception& e) {
        return Status::error(Status::Internal, name + ": validation failed: " + e.what());
    }
}

Status validateAsset(const Asset& asset, const std::string& name) { return fmt::validateTables(asset, name, false); }

}  // namespace lt
