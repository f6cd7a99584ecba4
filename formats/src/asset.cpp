// formats/src/asset.cpp -- the few out-of-line members of looptess/asset.h.
#include "looptess/asset.h"

#include <cstdint>
#include <limits>

namespace lt {

// Control vertices plus every level's refined vertices. Saturates at UINT32_MAX
// for an Asset that validateAsset would reject (rule 22: totals fit in uint32).
uint32_t Asset::totalVertexCount() const {
    uint64_t total = controlVertexCount();
    for (size_t l = 1; l < levels.size(); ++l) {
        const Refinement& r = levels[l].refinement;
        total += uint64_t(r.vertexParent.size()) + r.edgeVerts.size() / 4;
    }
    const uint64_t limit = std::numeric_limits<uint32_t>::max();
    return uint32_t(total < limit ? total : limit);
}

uint32_t Asset::editCount() const {
    uint64_t total = 0;
    for (const Level& level : levels) total += level.edits.op.size();
    const uint64_t limit = std::numeric_limits<uint32_t>::max();
    return uint32_t(total < limit ? total : limit);
}

uint32_t Asset::editDepth() const {
    uint32_t deepest = 0;
    for (uint32_t l = 0; l < levels.size(); ++l)
        if (levels[l].edits.count()) deepest = l;
    return deepest;
}

}  // namespace lt
