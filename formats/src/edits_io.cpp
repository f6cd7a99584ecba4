// formats/src/edits_io.cpp -- hierarchical edits in EXT_mesh_loop_subdivision (spec
// "Hierarchical edits"): the flat editValues array the writer emits and the reader
// splits, and the validity rules 40..44 of one level's VertexEdits.
//
// A level's edits are three level rows of kLevelProperties (editVertex, editStart,
// editOp, layout.cpp); the values of all levels are one extension-level accessor,
// in the flat edit order, so that a runtime can replace them alone:
//
//   level l:     editVertex  | v0 | v1 | v2 |          edited vertices, increasing
//                editStart   | 0 | 2 | 3 | 5 |         CSR into editOp
//                editOp      | a a | s | a a |         0 set, 1 add, 2 subtract
//   extension:   editValues  | level 0's | ... | level l's: xyz xyz xyz xyz xyz | ... |
#include "layout.h"

#include <cmath>
#include <string>

namespace lt::fmt {
namespace {

std::string str(uint64_t v) { return std::to_string(v); }
std::string at(size_t l, const char* prop) { return "levels[" + str(l) + "]." + prop; }
std::string at(size_t l, const char* prop, size_t i) { return at(l, prop) + "[" + str(i) + "]"; }

uint64_t editsBelow(const Asset& asset, size_t level) {
    uint64_t n = 0;
    for (size_t l = 0; l < level && l < asset.levels.size(); ++l) n += asset.levels[l].edits.op.size();
    return n;
}

// Rule 41: editStart is a CSR over editVertex into editOp in which every edited
// vertex has at least one edit.
Status checkStarts(const VertexEdits& e, size_t l, const std::string& file) {
    if (e.start.empty()) {
        if (e.vertex.empty() && e.op.empty()) return Status::ok();
        return ruleError(file, at(l, "editStart"), kRuleEditCsr,
                         "missing, but the level has " + str(e.vertex.size()) + " edited vertices and " +
                             str(e.op.size()) + " edits");
    }
    if (e.start.size() != e.vertex.size() + 1)
        return ruleError(file, at(l, "editStart"), kRuleEditCsr,
                         str(e.start.size()) + " entries, expected " + str(e.vertex.size() + 1) +
                             " (one per edited vertex plus one)");
    if (e.start[0] != 0)
        return ruleError(file, at(l, "editStart", 0), kRuleEditCsr, "is " + str(e.start[0]) + ", expected 0");
    for (size_t i = 1; i < e.start.size(); ++i)
        if (e.start[i] <= e.start[i - 1])
            return ruleError(file, at(l, "editStart", i), kRuleEditCsr,
                             "is " + str(e.start[i]) + ", not greater than the previous entry " + str(e.start[i - 1]) +
                                 " (edited vertex " + str(i - 1) + " needs at least one edit)");
    if (e.start.back() != e.op.size())
        return ruleError(
            file, at(l, "editStart", e.vertex.size()), kRuleEditCsr,
            "last entry " + str(e.start.back()) + " differs from the number of edits in editOp, " + str(e.op.size()));
    return Status::ok();
}

}  // namespace

Column editValues(const Asset& asset) {
    Column c;
    for (const Level& level : asset.levels) c.f.insert(c.f.end(), level.edits.value.begin(), level.edits.value.end());
    return c;
}

Status assignEditValues(Asset& asset, const Packed& values, const std::string& file, const std::string& path) {
    const uint64_t edits = editsBelow(asset, asset.levels.size());
    if (values.count == 0 && edits == 0) return Status::ok();
    if (values.count == 0)
        return ruleError(file, path, kRuleEditValues, "missing, but the levels have " + str(edits) + " edits");
    if (values.count != 3 * edits)
        return ruleError(file, path, kRuleEditValues,
                         str(values.count / 3) + " values, expected one per edit of levels 0 .. maxDepth = " +
                             str(asset.levels.size() - 1) + " (" + str(edits) + ")");
    size_t first = 0;  // the level's first edit in the flat order
    for (Level& level : asset.levels) {
        const size_t n = level.edits.op.size();
        loadValues(level.edits.value, Packed{values.data + 12 * first, 3 * n, kF32});
        first += n;
    }
    return Status::ok();
}

Status validateEdits(const Asset& asset, size_t l, const Range& range, const std::string& file) {
    const VertexEdits& e = asset.levels[l].edits;
    Status st = checkStarts(e, l, file);
    if (!st) return st;
    if (e.value.size() != 3 * uint64_t(e.op.size()))  // only in memory: the reader splits editValues by op counts
        return ruleError(
            file, "levels[" + str(l) + "]", kRuleEditValues,
            str(e.value.size()) + " edit values, expected 3 per edit (" + str(3 * uint64_t(e.op.size())) + ")");
    // Rule 42.
    for (size_t i = 0; i < e.vertex.size(); ++i) {
        const uint32_t v = e.vertex[i];
        if (!range.has(v))
            return ruleError(file, at(l, "editVertex", i), kRuleEditVertices,
                             "relative index " + str(uint32_t(v - range.begin)) + " (vertex " + str(v) +
                                 ") is not below level " + str(l) + "'s vertex count " + str(range.count));
        if (i > 0 && v <= e.vertex[i - 1])
            return ruleError(file, at(l, "editVertex", i), kRuleEditVertices,
                             "vertex " + str(v) + " does not follow the previous entry's vertex " +
                                 str(e.vertex[i - 1]) + " (edited vertices are distinct and increasing)");
    }
    // Rule 43.
    for (size_t k = 0; k < e.op.size(); ++k)
        if (uint8_t(e.op[k]) > uint8_t(EditOp::Subtract))
            return ruleError(file, at(l, "editOp", k), kRuleEditOps,
                             "operation " + str(uint8_t(e.op[k])) + " is not 0 (set), 1 (add) or 2 (subtract)");
    // Rule 44: values are stored in the extension's editValues, in the flat edit order.
    const uint64_t flat = editsBelow(asset, l);
    size_t vertex = 0;
    for (size_t j = 0; j < e.value.size(); ++j) {
        if (std::isfinite(e.value[j])) continue;
        const size_t k = j / 3;
        while (e.start[vertex + 1] <= k) ++vertex;
        return ruleError(file, "editValues[" + str(3 * (flat + k) + j % 3) + "]", kRuleEditFinite,
                         "level " + str(l) + " edit " + str(k) + " (of vertex " + str(e.vertex[vertex]) + ", editOp[" +
                             str(k) + "]): coordinate " + str(j % 3) + " is not finite");
    }
    return Status::ok();
}

}  // namespace lt::fmt
