// formats/src/control_mesh.cpp -- rules 10 and 11: the control mesh from the
// fallback primitive and controlVertex (layout.h, rebuildControlMesh).
#include "layout.h"

#include <algorithm>
#include <cstring>

namespace lt::fmt {

Status rebuildControlMesh(const std::vector<float>& positions, const std::vector<uint32_t>& indices,
                          const std::vector<uint32_t>& cv, const std::string& file, const std::string& cvPath,
                          const std::string& positionsPath, Asset& asset) {
    const uint64_t vcount = positions.size() / 3;
    auto str = [](uint64_t v) { return std::to_string(v); };
    const uint64_t n = cv.empty() ? 0 : *std::max_element(cv.begin(), cv.end()) + uint64_t(1);
    if (n > vcount)
        return ruleError(file, cvPath, kRuleControlVertexCover,
                         "maximum " + str(n - 1) + " leaves control vertices without a primitive vertex");
    std::vector<int64_t> first(size_t(n), -1);   // first primitive vertex of each control vertex
    for (size_t v = 0; v < vcount; ++v) {
        const uint32_t c = cv[v];
        if (first[c] < 0) {
            first[c] = int64_t(v);
        } else if (std::memcmp(&positions[3 * size_t(first[c])], &positions[3 * v], 12) != 0) {
            return ruleError(file, positionsPath, kRuleControlVertexPositions,
                             "vertices " + str(uint64_t(first[c])) + " and " + str(v) + " of control vertex " +
                                 str(c) + " have different positions");
        }
    }
    asset.positions.resize(size_t(3 * n));
    for (size_t c = 0; c < n; ++c) {
        if (first[c] < 0)
            return ruleError(file, cvPath, kRuleControlVertexCover, "no primitive vertex maps to control vertex " + str(c));
        std::memcpy(&asset.positions[3 * c], &positions[3 * size_t(first[c])], 12);
    }
    asset.faces.resize(indices.size());
    for (size_t i = 0; i < indices.size(); ++i) asset.faces[i] = cv[indices[i]];
    return Status::ok();
}

} // namespace lt::fmt
