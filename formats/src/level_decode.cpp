// formats/src/level_decode.cpp -- the reader's rule 15 and the decode of every
// level's tables from their accessors (layout.h decodeLevels), the levels' arrays
// decoded as independent tasks on a few threads.
#include "layout.h"
#include "parallel.h"

#include <algorithm>

namespace lt::fmt {
namespace {

// Rule 15 for level l: every row of a group holds the patch count (fixed by its
// first row) times its perItem values, or is absent when absence means all zero.
Status groupCounts(size_t l, const LevelRows& rows, const std::string& file, const std::string& extPath) {
    size_t count[3] = {};
    bool known[3] = {};
    for (size_t p = 0; p < kRowCount; ++p) {
        const LevelProperty& prop = kLevelProperties[p];
        const int g = int(prop.group);
        if (prop.group == Group::None) continue;
        const size_t values = rows[p].count;
        const std::string path = extPath + ".levels[" + std::to_string(l) + "]." + prop.name;
        if (!known[g]) {
            known[g] = true;
            count[g] = values / prop.perItem;
            if (values % prop.perItem == 0) continue;
            return ruleError(file, path, kRulePatchArrays,
                             std::to_string(values) + " values is not a multiple of " + std::to_string(prop.perItem));
        }
        if (values != count[g] * prop.perItem && !(values == 0 && prop.zeroWhenAbsent))
            return ruleError(file, path, kRulePatchArrays,
                             std::to_string(values) + " values, expected " + std::to_string(count[g] * prop.perItem) +
                                 " (" + std::to_string(prop.perItem) + " for each of " + std::to_string(count[g]) +
                                 " patches)");
    }
    return Status::ok();
}

// One task of decodeLevels: a level's patches (row kRowCount: both groups, which
// decodePatches reads together) or one of its ungrouped rows.
struct Task {
    size_t level = 0, row = 0;
    uint64_t values = 0;  // for the order: largest first
};

}  // namespace

size_t tableThreads(uint64_t values, size_t threads) {
    if (threads) return threads;
    return values < kParallelValues ? 1 : threadCount(0);
}

Status decodeLevels(Asset& asset, const std::vector<LevelRows>& rows, size_t threads, const std::string& file,
                    const std::string& extPath, bool& patchesChecked) {
    // Rule 15 first, level by level: decoding itself cannot fail, so the first
    // message is the one a serial decode would give.
    for (size_t l = 0; l < rows.size(); ++l)
        if (Status st = groupCounts(l, rows[l], file, extPath); !st) return st;

    std::vector<Task> tasks;
    uint64_t total = 0;
    for (size_t l = 0; l < rows.size(); ++l) {
        Task patches{l, kRowCount, 0};
        for (size_t p = 0; p < kRowCount; ++p) {
            total += rows[l][p].count;
            if (kLevelProperties[p].group != Group::None)
                patches.values += rows[l][p].count;
            else if (rows[l][p].count)
                tasks.push_back(Task{l, p, rows[l][p].count});
        }
        tasks.push_back(patches);
    }
    std::stable_sort(tasks.begin(), tasks.end(), [](const Task& a, const Task& b) { return a.values > b.values; });

    // Each task fills arrays that no other task touches; levels[l]'s
    // firstVertex and the control mesh are read only.
    std::vector<uint8_t> checked(rows.size(), 1);
    parallelTasks(tasks.size(), tableThreads(total, threads), [&](size_t t, size_t) {
        const size_t l = tasks[t].level;
        const LevelRows& r = rows[l];
        Level& level = asset.levels[l];
        const uint32_t first = level.refinement.firstVertex;
        if (tasks[t].row < kRowCount) {
            const LevelProperty& prop = kLevelProperties[tasks[t].row];
            const uint32_t parentFirst = l == 0 ? 0 : asset.levels[l - 1].refinement.firstVertex;
            prop.decode(level, r[tasks[t].row],
                        prop.base == Base::Parent ? parentFirst
                        : prop.base == Base::Own  ? first
                                                  : 0);
            return;
        }
        // The validator's patch limits (its numbering, should rule 22 hold).
        PatchLimits limits;
        limits.range = {
            first, l == 0 ? asset.controlVertexCount() : uint32_t(r[kVertexParent].count + r[kEdgeVerts].count / 4)};
        limits.level = uint32_t(l);
        limits.faces = asset.faceCount();
        limits.stencils = uint32_t(r[kLimitVertex].count);
        limits.finest = l + 1 == asset.levels.size();
        checked[l] = decodePatches(level, limits, r.data());
    });
    patchesChecked = std::all_of(checked.begin(), checked.end(), [](uint8_t c) { return c != 0; });
    return Status::ok();
}

}  // namespace lt::fmt
